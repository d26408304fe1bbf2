using System;

namespace ParticlePhysics.Integrators;

/// <summary>Checks shared by the integrators' <c>Step</c> methods, and their scratch-buffer sizing.</summary>
internal static class StepChecks
{
    public static void Check(IOdeSystem system, ReadOnlySpan<double> state, Span<double> next, double dt)
    {
        Guard.NotNull(system, nameof(system));
        Guard.PositiveFinite(dt, nameof(dt));
        if (state.Length != system.Dimension || next.Length != system.Dimension)
        {
            throw new ArgumentException(
                $"state and next must have the system's dimension {system.Dimension}; got {state.Length} and {next.Length}.");
        }

        if (state.Overlaps(next))
        {
            throw new ArgumentException("state and next must be distinct buffers.", nameof(next));
        }
    }

    public static ISecondOrderSystem SecondOrder(IOdeSystem system, string integrator) =>
        system as ISecondOrderSystem ?? throw new ArgumentException(
            $"{integrator} needs a position/velocity system (ISecondOrderSystem), such as a ParticleWorld; "
            + $"{system.GetType().Name} is a plain first-order ODE. Use explicit-euler, rk4 or rk45 for it.",
            nameof(system));

    /// <summary>Makes <paramref name="buffer"/> exactly <paramref name="length"/> long: allocates only when the dimension changes.</summary>
    public static double[] Sized(double[]? buffer, int length) =>
        buffer is not null && buffer.Length == length ? buffer : new double[length];
}
