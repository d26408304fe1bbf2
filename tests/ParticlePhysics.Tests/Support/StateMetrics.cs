using System;
using System.Security.Cryptography;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Support;

/// <summary>Error norms, bit hashes and runs to a time, shared by the tests.</summary>
internal static class StateMetrics
{
    /// <summary>Max absolute difference over all components (positions and velocities).</summary>
    public static double MaxAbsError(ReadOnlySpan<double> actual, ReadOnlySpan<double> expected)
    {
        Assert.Equal(expected.Length, actual.Length);
        var worst = 0.0;
        for (var i = 0; i < actual.Length; i++)
        {
            worst = Math.Max(worst, Math.Abs(actual[i] - expected[i]));
        }

        return worst;
    }

    /// <summary>SHA-256 of the raw bits of every value: equal hashes mean bit-identical states.</summary>
    public static string BitHash(ReadOnlySpan<double> values)
    {
        var bytes = new byte[values.Length * sizeof(double)];
        for (var i = 0; i < values.Length; i++)
        {
            BitConverter.TryWriteBytes(bytes.AsSpan(i * sizeof(double)), BitConverter.DoubleToInt64Bits(values[i]));
        }

        return Convert.ToHexString(SHA256.HashData(bytes));
    }

    /// <summary>Steps <paramref name="system"/> with a fixed dt for <paramref name="steps"/> steps.</summary>
    public static void Run(ParticleWorld system, IIntegrator integrator, double dt, int steps)
    {
        for (var s = 0; s < steps; s++)
        {
            system.Step(integrator, dt);
        }
    }

    /// <summary>
    /// Builds a fresh system, runs it to <paramref name="duration"/> with <paramref name="dt"/> (which must divide it),
    /// and returns the max error against the exact state.
    /// </summary>
    public static double ErrorAt(
        Func<ParticleWorld> build, IExactSolution exact, string integrator, double dt, double duration)
    {
        var system = build();
        var steps = checked((int)Math.Round(duration / dt));
        Assert.True(Math.Abs((steps * dt) - duration) < 1e-9 * duration, "dt must divide the duration");
        Run(system, IntegratorCatalog.Create(integrator), dt, steps);
        var expected = new double[system.Dimension];
        exact.ExactState(steps * dt, expected);
        return MaxAbsError(system.State, expected);
    }

    /// <summary>The observed orders log2(e(dt) / e(dt/2)) for consecutive halvings.</summary>
    public static double[] ObservedOrders(Func<double, double> errorAtDt, double dt, int levels)
    {
        var errors = new double[levels];
        for (var level = 0; level < levels; level++)
        {
            errors[level] = errorAtDt(dt / Math.Pow(2, level));
        }

        var orders = new double[levels - 1];
        for (var level = 0; level + 1 < levels; level++)
        {
            orders[level] = Math.Log2(errors[level] / errors[level + 1]);
        }

        return orders;
    }
}
