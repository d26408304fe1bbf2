using System;
using ParticlePhysics.Constraints;
using ParticlePhysics.Forces;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Scenarios;

/// <summary>
/// The course's chain: anchor (origin) - spring 1 (k1, rest length L1) - particle 1 - spring 2 (k2, L2) - particle 2,
/// with linear drag c1 on particle 1, c2 on particle 2, and gravity. Both particles start at rest on the vertical
/// axis, at (0, -L1, 0) and (0, -L1 - L2, 0) unless <see cref="Y1"/> or <see cref="Y2"/> say otherwise.
/// </summary>
/// <remarks>
/// While the motion stays on the axis with particle 1 below the anchor (and particle 2 below particle 1 when
/// L2 &gt; 0), the springs act along y and the system is linear:
/// m1 y1'' = -k1 (y1 + L1) - k2 (y1 - y2 - L2) - c1 y1' - m1 g and m2 y2'' = k2 (y1 - y2 - L2) - c2 y2' - m2 g.
/// The exact solution is exp(A t) applied to the affine state (y1, y2, v1, v2, 1).
/// </remarks>
public sealed class TwoMassChainScenario : IExactSolution
{
    /// <summary>The contract's default time step, in seconds.</summary>
    public const double DefaultTimeStep = 0.01;

    /// <summary>The contract's default duration, in seconds.</summary>
    public const double DefaultDuration = 20;

    private double _m1 = 1, _m2 = 1, _k1 = 10, _k2 = 10, _c1 = 0.5, _c2 = 0.5, _restLength1 = 1, _restLength2;
    private double? _y1, _y2;
    private double _gravity = Forces.Gravity.StandardAcceleration;

    /// <summary>m1, in kg (default 1).</summary>
    public double M1 { get => _m1; set { Guard.Mass(value, nameof(M1)); _m1 = value; } }

    /// <summary>m2, in kg (default 1).</summary>
    public double M2 { get => _m2; set { Guard.Mass(value, nameof(M2)); _m2 = value; } }

    /// <summary>k1, in N/m (default 10).</summary>
    public double K1 { get => _k1; set { Guard.NonNegativeFinite(value, nameof(K1)); _k1 = value; } }

    /// <summary>k2, in N/m (default 10).</summary>
    public double K2 { get => _k2; set { Guard.NonNegativeFinite(value, nameof(K2)); _k2 = value; } }

    /// <summary>c1, the linear drag on particle 1, in N s/m (default 0.5).</summary>
    public double C1 { get => _c1; set { Guard.NonNegativeFinite(value, nameof(C1)); _c1 = value; } }

    /// <summary>c2, the linear drag on particle 2, in N s/m (default 0.5).</summary>
    public double C2 { get => _c2; set { Guard.NonNegativeFinite(value, nameof(C2)); _c2 = value; } }

    /// <summary>L1, the rest length of spring 1, in m (default 1).</summary>
    public double RestLength1 { get => _restLength1; set { Guard.NonNegativeFinite(value, nameof(RestLength1)); _restLength1 = value; } }

    /// <summary>L2, the rest length of spring 2, in m (default 0, as in the course's equations).</summary>
    public double RestLength2 { get => _restLength2; set { Guard.NonNegativeFinite(value, nameof(RestLength2)); _restLength2 = value; } }

    /// <summary>The starting height of particle 1, in m (default -L1).</summary>
    public double Y1
    {
        get => _y1 ?? -_restLength1;
        set { Guard.Finite(value, nameof(Y1)); _y1 = value; }
    }

    /// <summary>The starting height of particle 2, in m (default -L1 - L2).</summary>
    public double Y2
    {
        get => _y2 ?? (-_restLength1 - _restLength2);
        set { Guard.Finite(value, nameof(Y2)); _y2 = value; }
    }

    /// <summary>g, in m/s^2 (default 9.81).</summary>
    public double Gravity { get => _gravity; set { Guard.NonNegativeFinite(value, nameof(Gravity)); _gravity = value; } }

    /// <summary>Builds the particle system: two particles, two springs, drag on each, gravity (and the springs' projection for xpbd).</summary>
    public ParticleWorld Build()
    {
        var system = new ParticleWorld(2);
        var first = system.AddParticle(new Vector3d(0, Y1, 0), _m1);
        var second = system.AddParticle(new Vector3d(0, Y2, 0), _m2);
        // A spring of rest length 0 is the contract's linear spring -k (x_i - x_j) (the course's L2 = 0), not the
        // rest-length formula at L = 0, which divides by the length and has no direction where the ends meet.
        var springs = new SpringNetwork(system);
        var linear = new ZeroLengthSprings(system);
        if (_restLength1 == 0.0)
        {
            linear.AddAnchored(first, Vector3d.Zero, _k1);
        }
        else
        {
            springs.AddAnchored(first, Vector3d.Zero, _k1, _restLength1);
        }

        if (_restLength2 == 0.0)
        {
            linear.Add(first, second, _k2);
        }
        else
        {
            springs.Add(first, second, _k2, _restLength2);
        }

        system.AddForce(springs);
        system.AddForce(linear);
        system.AddForce(new LinearDrag(_c1, system, new[] { first }));
        system.AddForce(new LinearDrag(_c2, system, new[] { second }));
        system.AddForce(Forces.Gravity.Down(_gravity));
        system.AddConstraints(new SpringProjection(springs)); // how xpbd steps the springs
        system.AddConstraints(new SpringProjection(linear));
        return system;
    }

    /// <summary>
    /// The matrix A of the affine system d/dt (y1, y2, v1, v2, 1) = A (y1, y2, v1, v2, 1) that holds while the
    /// chain hangs along the vertical axis.
    /// </summary>
    public double[,] SystemMatrix()
    {
        var a = new double[5, 5];
        a[0, 2] = 1;
        a[1, 3] = 1;
        a[2, 0] = -(_k1 + _k2) / _m1;
        a[2, 1] = _k2 / _m1;
        a[2, 2] = -_c1 / _m1;
        a[2, 4] = ((-_k1 * _restLength1) + (_k2 * _restLength2) - (_m1 * _gravity)) / _m1;
        a[3, 0] = _k2 / _m2;
        a[3, 1] = -_k2 / _m2;
        a[3, 3] = -_c2 / _m2;
        a[3, 4] = ((-_k2 * _restLength2) - (_m2 * _gravity)) / _m2;
        return a;
    }

    /// <inheritdoc />
    public void ExactState(double time, Span<double> state)
    {
        var propagator = MatrixExponential.Exp(SystemMatrix(), time);
        Span<double> start = stackalloc double[] { Y1, Y2, 0, 0, 1 };
        Span<double> now = stackalloc double[5];
        MatrixExponential.Apply(propagator, start, now);
        state.Slice(0, 12).Clear();
        state[1] = now[0];
        state[4] = now[1];
        state[6 + 1] = now[2];
        state[6 + 4] = now[3];
    }
}
