using System;

namespace ParticlePhysics.Forces;

/// <summary>
/// Hooke springs with a rest length and damping along their axis, between two particles or a particle and a fixed
/// anchor (zero velocity). With d = x_i - x_j, l = |d| and u = d / l:
/// F_i = -(k (l - L) + c (v_i - v_j) . u) u and F_j = -F_i. When l = 0 the direction is undefined and the force
/// is zero (never NaN). Potential energy: k (l - L)^2 / 2 per spring. One generator holds a whole network
/// (a cloth's thousands of springs) in flat arrays and is evaluated in one call.
/// </summary>
public sealed class SpringNetwork : IForceGenerator, IPotentialEnergy, IBoundForce
{
    // Pair parameters: k, L, c. Anchored parameters: ax, ay, az, k, L, c.
    private const int PairStride = 3;
    private const int AnchoredStride = 6;
    private readonly ForceElements _pairs = new(PairStride);
    private readonly ForceElements _anchored = new(AnchoredStride);
    private readonly ParticleSystem _system;

    /// <summary>An empty network for the particles of <paramref name="system"/>.</summary>
    public SpringNetwork(ParticleSystem system)
    {
        Guard.NotNull(system, nameof(system));
        _system = system;
    }

    /// <summary>The number of springs between two particles.</summary>
    public int Count => _pairs.Count;

    /// <summary>The number of springs between a particle and a fixed anchor.</summary>
    public int AnchoredCount => _anchored.Count;

    ParticleSystem? IBoundForce.System => _system;

    /// <summary>Adds a spring between two different existing particles.</summary>
    /// <param name="first">One end (i).</param>
    /// <param name="second">The other end (j).</param>
    /// <param name="stiffness">k, in N/m: a finite number &gt;= 0.</param>
    /// <param name="restLength">L, in metres: a finite number &gt;= 0.</param>
    /// <param name="damping">c, in N s/m, along the spring's axis: a finite number &gt;= 0.</param>
    /// <returns>The index of the new spring among the particle-particle springs.</returns>
    public int Add(int first, int second, double stiffness, double restLength, double damping = 0.0)
    {
        Guard.ParticleIndex(first, _system.Count, nameof(first));
        Guard.ParticleIndex(second, _system.Count, nameof(second));
        Guard.DistinctParticles(first, second, nameof(second));
        CheckParameters(stiffness, restLength, damping);
        Span<double> p = stackalloc double[] { stiffness, restLength, damping };
        return _pairs.Add(first, second, p);
    }

    /// <summary>Adds a spring between an existing particle and a fixed anchor point.</summary>
    /// <param name="particle">The particle (i).</param>
    /// <param name="anchor">The anchor's position (x_j), in metres; its velocity is zero.</param>
    /// <param name="stiffness">k, in N/m: a finite number &gt;= 0.</param>
    /// <param name="restLength">L, in metres: a finite number &gt;= 0.</param>
    /// <param name="damping">c, in N s/m, along the spring's axis: a finite number &gt;= 0.</param>
    /// <returns>The index of the new spring among the anchored springs.</returns>
    public int AddAnchored(int particle, Vector3d anchor, double stiffness, double restLength, double damping = 0.0)
    {
        Guard.ParticleIndex(particle, _system.Count, nameof(particle));
        Guard.Finite(anchor, nameof(anchor));
        CheckParameters(stiffness, restLength, damping);
        Span<double> p = stackalloc double[] { anchor.X, anchor.Y, anchor.Z, stiffness, restLength, damping };
        return _anchored.Add(particle, -1, p);
    }

    /// <summary>Changes the stiffness of a particle-particle spring (a finite number &gt;= 0, in N/m).</summary>
    public void SetStiffness(int spring, double stiffness)
    {
        _pairs.CheckIndex(spring, nameof(spring));
        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        _pairs.Parameters[PairStride * spring] = stiffness;
    }

    /// <summary>Changes the axial damping of a particle-particle spring (a finite number &gt;= 0, in N s/m).</summary>
    public void SetDamping(int spring, double damping)
    {
        _pairs.CheckIndex(spring, nameof(spring));
        Guard.NonNegativeFinite(damping, nameof(damping));
        _pairs.Parameters[(PairStride * spring) + 2] = damping;
    }

    /// <summary>The two particles joined by a particle-particle spring.</summary>
    public (int First, int Second) GetEnds(int spring)
    {
        _pairs.CheckIndex(spring, nameof(spring));
        return (_pairs.First[spring], _pairs.Second[spring]);
    }

    /// <summary>The rest length L of a particle-particle spring, in metres.</summary>
    public double GetRestLength(int spring)
    {
        _pairs.CheckIndex(spring, nameof(spring));
        return _pairs.Parameters[(PairStride * spring) + 1];
    }

    /// <inheritdoc />
    public void AddForces(in ParticleState state, Span<double> forces)
    {
        var x = state.Positions;
        var v = state.Velocities;
        var first = _pairs.First;
        var second = _pairs.Second;
        var p = _pairs.Parameters;
        for (var s = 0; s < _pairs.Count; s++)
        {
            int a = 3 * first[s], b = 3 * second[s], q = PairStride * s;
            double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
            var lengthSquared = (dx * dx) + (dy * dy) + (dz * dz);
            if (lengthSquared == 0.0)
            {
                continue;
            }

            var length = Math.Sqrt(lengthSquared);
            var inverse = 1.0 / length;
            double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
            var closing = ((v[a] - v[b]) * ux) + ((v[a + 1] - v[b + 1]) * uy) + ((v[a + 2] - v[b + 2]) * uz);
            var magnitude = (p[q] * (length - p[q + 1])) + (p[q + 2] * closing);
            double fx = magnitude * ux, fy = magnitude * uy, fz = magnitude * uz;
            forces[a] -= fx;
            forces[a + 1] -= fy;
            forces[a + 2] -= fz;
            forces[b] += fx;
            forces[b + 1] += fy;
            forces[b + 2] += fz;
        }

        var particle = _anchored.First;
        var r = _anchored.Parameters;
        for (var s = 0; s < _anchored.Count; s++)
        {
            int a = 3 * particle[s], q = AnchoredStride * s;
            double dx = x[a] - r[q], dy = x[a + 1] - r[q + 1], dz = x[a + 2] - r[q + 2];
            var lengthSquared = (dx * dx) + (dy * dy) + (dz * dz);
            if (lengthSquared == 0.0)
            {
                continue;
            }

            var length = Math.Sqrt(lengthSquared);
            var inverse = 1.0 / length;
            double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
            var closing = (v[a] * ux) + (v[a + 1] * uy) + (v[a + 2] * uz);
            var magnitude = (r[q + 3] * (length - r[q + 4])) + (r[q + 5] * closing);
            forces[a] -= magnitude * ux;
            forces[a + 1] -= magnitude * uy;
            forces[a + 2] -= magnitude * uz;
        }
    }

    /// <inheritdoc />
    public double PotentialEnergy(in ParticleState state)
    {
        var x = state.Positions;
        var sum = 0.0;
        for (var s = 0; s < _pairs.Count; s++)
        {
            int a = 3 * _pairs.First[s], b = 3 * _pairs.Second[s], q = PairStride * s;
            double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
            var stretch = Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz)) - _pairs.Parameters[q + 1];
            sum += 0.5 * _pairs.Parameters[q] * stretch * stretch;
        }

        var r = _anchored.Parameters;
        for (var s = 0; s < _anchored.Count; s++)
        {
            int a = 3 * _anchored.First[s], q = AnchoredStride * s;
            double dx = x[a] - r[q], dy = x[a + 1] - r[q + 1], dz = x[a + 2] - r[q + 2];
            var stretch = Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz)) - r[q + 4];
            sum += 0.5 * r[q + 3] * stretch * stretch;
        }

        return sum;
    }

    private static void CheckParameters(double stiffness, double restLength, double damping)
    {
        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        Guard.NonNegativeFinite(restLength, nameof(restLength));
        Guard.NonNegativeFinite(damping, nameof(damping));
    }
}
