using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Bodies;

// Rigid bodies: the prediction along the rotation, the exact projection and the rigid velocity field (see the class remarks).
public sealed partial class ShapeMatching
{
    /// <summary>
    /// The rigid projection of a substep. With <paramref name="fromVelocities"/> (a force-based step's end) the angular
    /// momentum is that of the end velocities about the start's offsets instead of the chords', and the velocities are
    /// set to the rigid field at once: nothing comes between the projection and the velocities there.
    /// </summary>
    private void ProjectRigid(int body, in ConstraintContext context, bool fromVelocities = false)
    {
        var (first, end) = (_start[body], _start[body + 1]);
        var x0 = context.StartPositions.ForReading();
        var x = context.Positions;
        var m = context.Masses.ForReading();
        var w = context.InverseMasses.ForReading();
        var (mass, c, restCentre) = Centres(first, end, x, m);
        var (_, c0, _) = Centres(first, end, x0, m);

        // The angular momentum of the prediction about the start's centre of mass: the start's spin plus the forces' torques.
        var inverseH = 1.0 / context.Dt;
        var v = context.Velocities;
        var momentum = Vector3d.Zero;
        var velocity = Vector3d.Zero;
        var (particles, offsets, goals) = (_particles, _rest, _goals);
        for (var k = first; k < end; k++)
        {
            var i = particles[k];
            var start = At(x0, i);
            var vi = fromVelocities ? At(v, i) : (At(x, i) - start) * inverseH;
            momentum += m[i] * Vector3d.Cross(start - c0, vi);
            velocity += m[i] * vi;
        }

        // Turn by exp(omega h), omega = I^-1 L taken at the half-way orientation: the midpoint rule, second order.
        var h = context.Dt;
        var q0 = _orientation[body];
        var inertia = InertiaOf(body, m, restCentre);
        var omega = inertia.AngularVelocity(q0, momentum);
        var half = (Quaternion4d.FromRotationVector((0.5 * h) * omega) * q0).Normalized();
        omega = inertia.AngularVelocity(half, momentum);
        var q = (Quaternion4d.FromRotationVector(h * omega) * q0).Normalized();
        for (var k = first; k < end; k++)
        {
            var i = particles[k];
            var goal = c + q.Rotate(offsets[k] - restCentre);
            goals[k] = goal;
            if (w[i] != 0.0)
            {
                Put(x, i, goal);
            }
        }

        _predicted[body] = q;
        _momentum[body] = momentum;
        if (fromVelocities)
        {
            velocity /= mass;
            var spin = inertia.AngularVelocity(q, momentum);
            for (var k = first; k < end; k++)
            {
                var i = particles[k];
                if (w[i] != 0.0)
                {
                    Put(v, i, velocity + Vector3d.Cross(spin, goals[k] - c));
                }
            }

            _orientation[body] = q;
        }
    }

    private void SolveRigidVelocities(int body, in ConstraintContext context)
    {
        var (first, end) = (_start[body], _start[body + 1]);
        var x0 = context.StartPositions.ForReading();
        var x = context.Positions;
        var v = context.Velocities;
        var m = context.Masses.ForReading();
        var w = context.InverseMasses.ForReading();
        var (mass, c, restCentre) = Centres(first, end, x, m);
        var inverseH = 1.0 / context.Dt;

        // What the velocities hold beyond the chords to the goals is what other sets did since the projection
        // (contacts' pushes and impulses): add its angular momentum to the prediction's, whose chords fall short of it
        // by the (omega h)^2 that the velocity field corrects.
        var velocity = Vector3d.Zero;
        var extra = Vector3d.Zero;
        var covariance = default(CovarianceSum);
        var (particles, offsets, goals) = (_particles, _rest, _goals);
        for (var k = first; k < end; k++)
        {
            var i = particles[k];
            var mi = m[i];
            var r = At(x, i) - c;
            var vi = At(v, i);
            velocity += mi * vi;
            extra += mi * Vector3d.Cross(r, vi - ((goals[k] - At(x0, i)) * inverseH));
            covariance.Add(mi * r, offsets[k] - restCentre);
        }

        velocity /= mass;
        var q = covariance.Rotation(_predicted[body]);
        var omega = InertiaOf(body, m, restCentre).AngularVelocity(q, _momentum[body] + extra);
        for (var k = first; k < end; k++)
        {
            var i = particles[k];
            if (w[i] != 0.0)
            {
                Put(v, i, velocity + Vector3d.Cross(omega, At(x, i) - c));
            }
        }

        _orientation[body] = q;
    }

    /// <summary>The total mass, the centre of mass of <paramref name="x"/>, and the mass-weighted mean of the rest offsets.</summary>
    private (double Mass, Vector3d Centre, Vector3d RestCentre) Centres(int first, int end, Span<double> x, Span<double> m)
    {
        var mass = 0.0;
        var centre = Vector3d.Zero;
        var rest = Vector3d.Zero;
        var (particles, offsets) = (_particles, _rest); // locals: the loop reads no field again
        for (var k = first; k < end; k++)
        {
            var i = particles[k];
            mass += m[i];
            centre += m[i] * At(x, i);
            rest += m[i] * offsets[k];
        }

        return (mass, centre / mass, rest / mass);
    }

    /// <summary>The inertia of body <paramref name="body"/>'s rest offsets about <paramref name="restCentre"/>, with the masses as they are now.</summary>
    private RestInertia InertiaOf(int body, Span<double> m, Vector3d restCentre)
    {
        var (first, count) = (_start[body], _start[body + 1] - _start[body]);
        return RestInertia.Of(_particles.AsSpan(first, count), _rest.AsSpan(first, count), m, restCentre);
    }

    /// <summary>Whether the rest shape has an invertible inertia: its particles do not all lie on one line.</summary>
    private static bool InertiaIsRegular(Vector3d[] rest, Span<int> particles, Span<double> m)
    {
        // The offsets are about the centre of mass already; the smallest principal moment vanishes only on a line.
        var inertia = RestInertia.Of(particles, rest, m, Vector3d.Zero);
        var det = inertia.Determinant;
        var size = inertia.SecondMoment;
        return DoubleChecks.IsFinite(det) && det > 1e-9 * size * size * size;
    }
}
