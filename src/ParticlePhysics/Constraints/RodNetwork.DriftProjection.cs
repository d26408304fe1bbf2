using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Constraints;

// The constraint stage after a force-based step (Resolve): the drift projected away by Newton in the mass metric,
// SHAKE after a kick and a drift, then the velocities.
public sealed partial class RodNetwork
{
    // The drift projection stops when every violated length is within this fraction of L, or after MaxNewtonIterations.
    private const double ProjectionTolerance = 1e-13;
    private const int MaxNewtonIterations = 20;

    // SHAKE's projection after a kick and a drift: the multipliers of its accepted iterations, and of the last one.
    private double[] _kick = Array.Empty<double>();
    private double[] _kickStep = Array.Empty<double>();

    /// <inheritdoc />
    /// <remarks>
    /// Removes the drift that the step left: positions onto C = 0 (rods, and cables stretched beyond their length) by
    /// Newton's method in the mass metric, then velocities onto C' = 0 (rods, and taut cables that separate: the
    /// inelastic impulse of a cable going taut).
    /// </remarks>
    public void Resolve(in ConstraintContext context)
    {
        if (_count == 0)
        {
            return;
        }

        EnsureTopology(context.Count);
        var w = context.InverseMasses.ForReading();
        var x = context.Positions;
        if (context.KickDrift)
        {
            ProjectIntoTheKick(context, w);
        }

        // Newton in the mass metric along the current gradients: the whole projection after the other integrators;
        // after a kick and a drift only a check, unless SHAKE's iteration above stopped short of the tolerance.
        for (var iteration = 0; iteration < MaxNewtonIterations; iteration++)
        {
            var worst = 0.0;
            for (var r = 0; r < _count; r++)
            {
                var l = Distance(x, r, out var dx, out var dy, out var dz);
                var violation = l - _length[r];
                var active = l > 0.0 && (!_cable[r] || violation > 0.0);
                _active[r] = active;
                _rhs[r] = -violation;
                if (active)
                {
                    worst = Math.Max(worst, Math.Abs(violation) / _length[r]);
                    SetGradient(r, dx / l, dy / l, dz / l);
                }
                else
                {
                    SetGradient(r, 0, 0, 0);
                }
            }

            if (worst <= ProjectionTolerance)
            {
                break;
            }

            Solve(w);
            ApplyCorrection(w, x);
        }

        var vel = context.Velocities;
        var any = false;
        for (var r = 0; r < _count; r++)
        {
            var l = Distance(x, r, out var dx, out var dy, out var dz);
            var rate = 0.0;
            if (l > 0.0)
            {
                dx /= l;
                dy /= l;
                dz /= l;
                int i = 3 * _first[r], j = 3 * _second[r];
                rate = (dx * vel[i]) + (dy * vel[i + 1]) + (dz * vel[i + 2]);
                if (j >= 0)
                {
                    rate -= (dx * vel[j]) + (dy * vel[j + 1]) + (dz * vel[j + 2]);
                }
            }

            var active = l > 0.0 && (!_cable[r] || (l >= _length[r] * (1.0 - TautTolerance) && rate > 0.0));
            _active[r] = active;
            any |= active;
            SetGradient(r, dx, dy, dz);
            _rhs[r] = -rate;
        }

        if (any)
        {
            SolveWithPullingCables(w);
            ApplyCorrection(w, vel);
        }
    }

    /// <summary>
    /// SHAKE's projection after a kick and a drift (<see cref="ConstraintContext.KickDrift"/>): the end positions move
    /// along the gradients at the step's start, x1 += W J(x0)^T mu with C(x1) = 0, and the end velocities by the same
    /// over dt, so that x1 = x0 + dt v1 still holds. Why, in the smooth form of <see cref="AddConstraintForces"/>
    /// (A = J W J^T, b_r = |e_r|^2 the rods' centripetal terms, lambda the explicit tension, Q the applied forces): the
    /// kick leaves the tangent space, J(x0) v1 = -dt b, and the kick and the drift change the energy by
    /// (dt^2 / 2) (lambda^T A lambda - |Q|_W^2), in which (dt^2 / 2) b^T A^-1 b grows as the fourth power of the
    /// speeds. Moving the positions alone onto the rods leaves that energy in the velocities, so chains run away. The
    /// end lies off the rods by C(x1) = -dt^2 b / 2, so A mu = dt^2 b / 2 to leading order, and with mu folded into the
    /// kick v1 . M dv = (J(x0) v1) . mu / dt = -(dt^2 / 2) b^T A^-1 b takes that back: the step is the constrained
    /// symplectic Euler method (Hairer, Lubich and Wanner, "Geometric Numerical Integration", VII.1),
    /// v1 = v0 + dt W (Q(x0) + J(x0)^T Lambda), x1 = x0 + dt v1, C(x1) = 0, then the velocities projected onto C' = 0
    /// at x1 (RATTLE's second projection, which only removes energy), and its energy stays bounded. On a uniform
    /// rotation it keeps the speed exactly and turns by asin(h omega). The gradients must be the start's: along the
    /// end's, dv would lie along the normals that the velocity projection removes, and change nothing.
    /// mu is found by the quasi-Newton iteration of SHAKE, (J(x0) W J(x0)^T) dmu = -C(x): it contracts as fast as the
    /// rods turn in a step. An iteration that does not shrink the largest violation (a rod that turned by nearly a right
    /// angle, or a state far off its rods) is undone, and the Newton projection along the current gradients finishes
    /// without touching the velocities, as after the other integrators.
    /// </summary>
    private void ProjectIntoTheKick(in ConstraintContext context, Span<double> w)
    {
        var x = context.Positions;
        var x0 = context.StartPositions.ForReading();
        for (var r = 0; r < _count; r++)
        {
            var l0 = Distance(x0, r, out var dx, out var dy, out var dz);
            if (l0 > 0.0)
            {
                SetGradient(r, dx / l0, dy / l0, dz / l0);
            }
            else
            {
                SetGradient(r, 0, 0, 0);
            }

            _kick[r] = 0.0;
        }

        var worst = KickViolations(x);
        var any = false;
        for (var iteration = 0; iteration < MaxNewtonIterations && worst > ProjectionTolerance; iteration++)
        {
            Solve(w);
            for (var r = 0; r < _count; r++)
            {
                _kickStep[r] = _active[r] ? _lambda[r] : 0.0;
            }

            AddStartCorrection(w, x, _kickStep, 1.0);
            var next = KickViolations(x);
            if (!(next < worst))
            {
                AddStartCorrection(w, x, _kickStep, -1.0);
                break;
            }

            for (var r = 0; r < _count; r++)
            {
                _kick[r] += _kickStep[r];
                any |= _kickStep[r] != 0.0;
            }

            worst = next;
        }

        if (any)
        {
            AddStartCorrection(w, context.Velocities, _kick, 1.0 / context.Dt);
        }
    }

    /// <summary>
    /// The violations at <paramref name="x"/> for SHAKE's iteration (the start gradients set): the right-hand side -C,
    /// the active links (a start direction, and a rod, or a cable stretched beyond its length); returns the largest
    /// |C| / L.
    /// </summary>
    private double KickViolations(Span<double> x)
    {
        var worst = 0.0;
        for (var r = 0; r < _count; r++)
        {
            var violation = Distance(x, r, out _, out _, out _) - _length[r];
            var active = GradientDot(r, r) > 0.0 && (!_cable[r] || violation > 0.0);
            _active[r] = active;
            _rhs[r] = -violation;
            if (active)
            {
                worst = Math.Max(worst, Math.Abs(violation) / _length[r]);
            }
        }

        return worst;
    }

    /// <summary>Adds W J^T (scale m) into <paramref name="target"/> for every link with m_r != 0 (J's rows the gradients set).</summary>
    private void AddStartCorrection(Span<double> w, Span<double> target, double[] multipliers, double scale)
    {
        for (var r = 0; r < _count; r++)
        {
            var m = multipliers[r];
            if (m == 0.0)
            {
                continue;
            }

            int i = 3 * _first[r], j = 3 * _second[r], g = 3 * r;
            var si = scale * m * w[_first[r]];
            target[i] += si * _gradient[g];
            target[i + 1] += si * _gradient[g + 1];
            target[i + 2] += si * _gradient[g + 2];
            if (j >= 0)
            {
                var sj = scale * m * w[_second[r]];
                target[j] -= sj * _gradient[g];
                target[j + 1] -= sj * _gradient[g + 1];
                target[j + 2] -= sj * _gradient[g + 2];
            }
        }
    }
}
