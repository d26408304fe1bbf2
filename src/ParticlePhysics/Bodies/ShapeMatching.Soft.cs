using ParticlePhysics.Numerics;

namespace ParticlePhysics.Bodies;

// Soft bodies: Müller et al.'s projection towards the goals by the fraction s.
public sealed partial class ShapeMatching
{
    private void ProjectSoft(int body, in ConstraintContext context, bool kickVelocities)
    {
        var (first, end) = (_start[body], _start[body + 1]);
        var x = context.Positions;
        var v = context.Velocities;
        var m = context.Masses.ForReading();
        var w = context.InverseMasses.ForReading();
        var (_, c, restCentre) = Centres(first, end, x, m);
        double a00 = 0, a01 = 0, a02 = 0, a10 = 0, a11 = 0, a12 = 0, a20 = 0, a21 = 0, a22 = 0;
        for (var k = first; k < end; k++)
        {
            var i = _particles[k];
            var p = m[i] * (At(x, i) - c);
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

        var q = RotationExtraction.Extract(a00, a01, a02, a10, a11, a12, a20, a21, a22, _orientation[body]);
        _orientation[body] = q;
        var s = _stiffness[body];
        var inverseDt = 1.0 / context.Dt;
        for (var k = first; k < end; k++)
        {
            var i = _particles[k];
            if (w[i] == 0.0)
            {
                continue;
            }

            var xi = At(x, i);
            var move = s * (c + q.Rotate(_rest[k] - restCentre) - xi);
            Put(x, i, xi + move);
            if (kickVelocities)
            {
                Put(v, i, At(v, i) + (move * inverseDt));
            }
        }
    }
}
