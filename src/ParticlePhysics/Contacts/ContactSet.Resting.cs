using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>Stage 4 of <see cref="ContactSet.Resolve"/>: the particles that came to rest slide with exact Coulomb friction.</summary>
public sealed partial class ContactSet
{
    /// <summary>
    /// Each particle that came to rest on an obstacle at time s stays on its surface for the rest of the step,
    /// tau = T - s: its end position is put back on the surface and its approaching normal velocity taken out; that
    /// normal velocity change dv_n is the normal impulse per unit mass N tau / m, so friction may take mu dv_n of
    /// tangential velocity, spread evenly over tau as the deceleration f = mu dv_n / tau (<see cref="CoulombSlide"/>),
    /// against the direction it slid in when it came to rest, or, at rest, against the whole applied tangential force.
    /// The applied tangential acceleration is the integrator's change of tangential velocity over tau (exact under
    /// constant forces for every integrator), and what the integrator moved since the particle came to rest, relative to
    /// the obstacle, is replaced along friction's line by the frictional motion, so that on a plane under constant forces,
    /// under every integrator, a slide stops after v0^2 / (2 mu g) and a particle on an incline sticks exactly when
    /// tan(theta) &lt;= mu.
    /// </summary>
    private void ApplyRestingFriction(in ConstraintContext context)
    {
        var n = context.Count;
        var x = context.Positions;
        var v = context.Velocities;
        var radii = context.Radii.ForReading();
        var end = context.Time + context.Dt;
        for (var i = 0; i < n; i++)
        {
            var k = _resting.FirstObstacle(i);
            if (k < 0)
            {
                continue;
            }

            var obstacle = _obstacles[k];
            var position = Read(x, i);
            var q = position - obstacle.OffsetAt(end);
            var gap = obstacle.Distance(q.X, q.Y, q.Z, out var nx, out var ny, out var nz) - Radius(radii, i);
            var normal = new Vector3d(nx, ny, nz);
            var velocity = Read(v, i);
            var before = velocity;
            var relative = velocity - obstacle.Velocity;
            var un = Vector3d.Dot(relative, normal);
            if (!(gap < 0.0) && !(gap <= ContactSearch.Tolerance && un < 0.0))
            {
                continue; // it left the surface within the step: no normal force, no friction
            }

            if (gap < 0.0)
            {
                position -= gap * normal;
            }

            if (un < 0.0)
            {
                velocity -= un * normal;
                relative -= un * normal;
            }

            var tau = context.Dt - _resting.Time(i);
            var f = FrictionWith(obstacle, i) * Math.Max(-un, 0.0);
            if (f > 0.0 && tau > 0.0)
            {
                // The tangential velocity at the start of the rest and at the end, and the displacement since the
                // particle came to rest (relative to the obstacle), in the end's tangent plane.
                var rest = _resting.Tangent(i);
                var w0 = rest - (Vector3d.Dot(rest, normal) * normal);
                var w1 = relative - (Vector3d.Dot(relative, normal) * normal);
                var moved = position - obstacle.OffsetAt(end) - _resting.Point(i);
                moved -= Vector3d.Dot(moved, normal) * normal;
                CoulombSlide.Correction(w0, w1, f / tau, tau, moved, out var dw, out var dx);
                velocity += dw;
                position += dx;
            }

            Write(x, i, position);
            Write(v, i, velocity);
            React(in context, i, k, velocity - before, position, normal, end);
        }
    }
}
