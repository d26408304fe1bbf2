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
        for (var k = first; k < end; k++)
        {
            var i = _particles[k];
            var start = At(x0, i);
            var vi = fromVelocities ? At(v, i) : (At(x, i) - start) * inverseH;
            momentum += m[i] * Vector3d.Cross(start - c0, vi);
            velocity += m[i] * vi;
        }

        // Turn by exp(omega h), omega = I^-1 L taken at the half-way orientation: the midpoint rule, second order.
        var h = context.Dt;
        var q0 = _orientation[body];
        var omega = AngularVelocity(first, end, m, restCentre, q0, momentum);
        var half = (Quaternion4d.FromRotationVector((0.5 * h) * omega) * q0).Normalized();
        omega = AngularVelocity(first, end, m, restCentre, half, momentum);
        var q = (Quaternion4d.FromRotationVector(h * omega) * q0).Normalized();
        for (var k = first; k < end; k++)
        {
            var i = _particles[k];
            var goal = c + q.Rotate(_rest[k] - restCentre);
            _goals[k] = goal;
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
            var spin = AngularVelocity(first, end, m, restCentre, q, momentum);
            for (var k = first; k < end; k++)
            {
                var i = _particles[k];
                if (w[i] != 0.0)
                {
                    Put(v, i, velocity + Vector3d.Cross(spin, _goals[k] - c));
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
        double a00 = 0, a01 = 0, a02 = 0, a10 = 0, a11 = 0, a12 = 0, a20 = 0, a21 = 0, a22 = 0;
        for (var k = first; k < end; k++)
        {
            var i = _particles[k];
            var mi = m[i];
            var r = At(x, i) - c;
            var vi = At(v, i);
            velocity += mi * vi;
            extra += mi * Vector3d.Cross(r, vi - ((_goals[k] - At(x0, i)) * inverseH));
            var p = mi * r;
            var d = _rest[k] - restCentre;
            a00 += p.X * d.X;
            a01 += p.X * d.Y;
            a02 += p.X * d.Z;
            a10 += p.Y * d.X;
            a11 += p.Y * d.Y;
            a12 += p.Y * d.Z;
            a20 += p.Z * d.X;
            a21 += p.Z * d.Y;
            a22 += p.Z * d.Z;
        }

        velocity /= mass;
        var q = RotationExtraction.Extract(a00, a01, a02, a10, a11, a12, a20, a21, a22, _predicted[body]);
        var omega = AngularVelocity(first, end, m, restCentre, q, _momentum[body] + extra);
        for (var k = first; k < end; k++)
        {
            var i = _particles[k];
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
        for (var k = first; k < end; k++)
        {
            var i = _particles[k];
            mass += m[i];
            centre += m[i] * At(x, i);
            rest += m[i] * _rest[k];
        }

        return (mass, centre / mass, rest / mass);
    }

    /// <summary>
    /// omega = I^-1 L with I = R I_0 R^T, I_0 = sum m (|d|^2 1 - d d^T) of the rest offsets d about their centre of mass,
    /// solved in the body's frame by cofactors; 0 for a body with no inertia (one particle).
    /// </summary>
    private Vector3d AngularVelocity(int first, int end, Span<double> m, Vector3d restCentre, Quaternion4d rotation, Vector3d momentum)
    {
        var (xx, xy, xz, yy, yz, zz) = RestInertia(first, end, m, restCentre);
        var b = rotation.RotateInverse(momentum);
        var c00 = (yy * zz) - (yz * yz);
        var c01 = (xz * yz) - (xy * zz);
        var c02 = (xy * yz) - (xz * yy);
        var det = (xx * c00) + (xy * c01) + (xz * c02);
        if (!(det > 0.0))
        {
            return Vector3d.Zero;
        }

        var c11 = (xx * zz) - (xz * xz);
        var c12 = (xy * xz) - (xx * yz);
        var c22 = (xx * yy) - (xy * xy);
        var y = new Vector3d(
            ((c00 * b.X) + (c01 * b.Y) + (c02 * b.Z)) / det,
            ((c01 * b.X) + (c11 * b.Y) + (c12 * b.Z)) / det,
            ((c02 * b.X) + (c12 * b.Y) + (c22 * b.Z)) / det);
        return rotation.Rotate(y);
    }

    private (double Xx, double Xy, double Xz, double Yy, double Yz, double Zz) RestInertia(int first, int end, Span<double> m, Vector3d restCentre)
    {
        double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0;
        for (var k = first; k < end; k++)
        {
            var mi = m[_particles[k]];
            var d = _rest[k] - restCentre;
            double dx2 = d.X * d.X, dy2 = d.Y * d.Y, dz2 = d.Z * d.Z;
            xx += mi * (dy2 + dz2);
            yy += mi * (dx2 + dz2);
            zz += mi * (dx2 + dy2);
            xy -= mi * d.X * d.Y;
            xz -= mi * d.X * d.Z;
            yz -= mi * d.Y * d.Z;
        }

        return (xx, xy, xz, yy, yz, zz);
    }

    /// <summary>Whether the rest shape has an invertible inertia: its particles do not all lie on one line.</summary>
    private static bool InertiaIsRegular(Vector3d[] rest, Span<int> particles, Span<double> m)
    {
        // The offsets are about the centre of mass already; the smallest principal moment vanishes only on a line.
        double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0, size = 0;
        for (var k = 0; k < rest.Length; k++)
        {
            var mi = m[particles[k]];
            var d = rest[k];
            xx += mi * ((d.Y * d.Y) + (d.Z * d.Z));
            yy += mi * ((d.X * d.X) + (d.Z * d.Z));
            zz += mi * ((d.X * d.X) + (d.Y * d.Y));
            xy -= mi * d.X * d.Y;
            xz -= mi * d.X * d.Z;
            yz -= mi * d.Y * d.Z;
            size += mi * d.LengthSquared;
        }

        var det = (xx * ((yy * zz) - (yz * yz))) - (xy * ((xy * zz) - (yz * xz))) + (xz * ((xy * yz) - (yy * xz)));
        return DoubleChecks.IsFinite(det) && det > 1e-9 * size * size * size;
    }
}
