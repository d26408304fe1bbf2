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
        var covariance = default(CovarianceSum);
        for (var k = first; k < end; k++)
        {
            var i = _particles[k];
            covariance.Add(m[i] * (At(x, i) - c), _rest[k] - restCentre);
        }

        var q = covariance.Rotation(_orientation[body]);
        _orientation[body] = q;
        var s = _stiffness[body];
        var plastic = IsPlastic(body);
        var inverseDt = 1.0 / context.Dt;
        for (var k = first; k < end; k++)
        {
            var i = _particles[k];
            if (w[i] == 0.0)
            {
                continue;
            }

            var xi = At(x, i);
            var goal = c + q.Rotate(_rest[k] - restCentre);
            var move = s * (goal - xi);
            if (plastic)
            {
                Yield(body, k, xi, goal, q);
            }

            Put(x, i, xi + move);
            if (kickVelocities)
            {
                Put(v, i, At(v, i) + (move * inverseDt));
            }
        }
    }
}
