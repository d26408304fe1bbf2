using System;
using ParticlePhysics.Internal;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Forces;

/// <summary>
/// Uniform gravity: F_i = m_i g on every particle, with g = (0, -9.81, 0) m/s^2 by default (y up).
/// Potential energy: U = -sum m_i g . x_i. Its Jacobian is zero: implicit integrators treat it exactly.
/// </summary>
public sealed class Gravity : IParticleLinks, IForceGenerator, IPotentialEnergy, IForceJacobian, IUniformJacobianProduct
{
    /// <summary>Standard gravity, 9.81 m/s^2, as the course uses it.</summary>
    public const double StandardAcceleration = 9.81;

    private Vector3d _acceleration;
    private int _revision;

    /// <summary>Gravity of <see cref="StandardAcceleration"/> pointing down (-y).</summary>
    public Gravity()
        : this(new Vector3d(0, -StandardAcceleration, 0))
    {
    }

    /// <summary>Gravity with the given acceleration vector g, in m/s^2.</summary>
    public Gravity(Vector3d acceleration)
    {
        Guard.Finite(acceleration, nameof(acceleration));
        _acceleration = acceleration;
    }

    /// <summary>Gravity of magnitude <paramref name="g"/> m/s^2 pointing down (-y).</summary>
    public static Gravity Down(double g)
    {
        Guard.NonNegativeFinite(g, nameof(g));
        return new Gravity(new Vector3d(0, -g, 0));
    }

    /// <summary>The acceleration vector g, in m/s^2; can be changed between steps.</summary>
    public Vector3d Acceleration
    {
        get => _acceleration;
        set
        {
            Guard.Finite(value, nameof(Acceleration));
            _acceleration = value;
            _revision++;
        }
    }

    /// <inheritdoc />
    public int Revision => _revision;

    /// <inheritdoc />
    /// <remarks>Gravity acts on each particle alone: it links none.</remarks>
    public void AddLinks(ParticleIslands islands)
    {
    }

    /// <inheritdoc />
    public void AddForces(in ParticleState state, Span<double> forces)
    {
        var masses = state.Masses.ForReading();
        double gx = _acceleration.X, gy = _acceleration.Y, gz = _acceleration.Z;
        if (gx == 0.0 && gz == 0.0)
        {
            // The usual case, gravity along y: one addition per particle instead of three (adding 0 changes nothing),
            // through pointers once the sizes are checked (a strided store would otherwise be bounds-checked each time).
            if (forces.Length < 3 * masses.Length)
            {
                throw new ArgumentException(
                    $"forces must hold 3 values per particle ({3 * masses.Length}); it holds {forces.Length}.", nameof(forces));
            }

            unsafe
            {
                fixed (double* m = masses, f = forces)
                {
                    var fy = f + 1;
                    for (double* mi = m, last = m + masses.Length; mi < last; mi++, fy += 3)
                    {
                        *fy += *mi * gy;
                    }
                }
            }

            return;
        }

        for (var i = 0; i < masses.Length; i++)
        {
            var m = masses[i];
            forces[3 * i] += m * gx;
            forces[(3 * i) + 1] += m * gy;
            forces[(3 * i) + 2] += m * gz;
        }
    }

    /// <inheritdoc />
    public double PotentialEnergy(in ParticleState state)
    {
        var x = state.Positions.ForReading();
        var masses = state.Masses.ForReading();
        var sum = 0.0;
        for (var i = 0; i < masses.Length; i++)
        {
            sum -= masses[i] * ((_acceleration.X * x[3 * i]) + (_acceleration.Y * x[(3 * i) + 1])
                + (_acceleration.Z * x[(3 * i) + 2]));
        }

        return sum;
    }

    /// <inheritdoc />
    public void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        // A uniform field: df/dx = df/dv = 0.
    }

    /// <inheritdoc />
    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
    }

    /// <inheritdoc />
    bool IUniformJacobianProduct.TryGetUniformProduct(out double coefficient, out bool none)
    {
        coefficient = 0.0;
        none = true;
        return true;
    }

    /// <inheritdoc />
    public void AddDiagonalBlocks(Span<double> blocks)
    {
    }
}
