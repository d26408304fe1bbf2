using System;
using MathNet.Numerics.OdeSolvers;
using MathNetVector = MathNet.Numerics.LinearAlgebra.Vector<double>;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The peer: Math.NET Numerics' classical RK4 (<see cref="RungeKutta.FourthOrder(MathNetVector, double, double, int, Func{double, MathNetVector, MathNetVector})"/>)
/// on the same cloth ODE. Its right-hand side wraps the library's own force code, as a user of Math.NET would:
/// copy the vector into an array, call <see cref="ParticleWorld.Evaluate"/>, and return the derivative as a new
/// vector (Math.NET's solver allocates a new vector per stage and per operation anyway, and keeps the whole
/// trajectory). The copy reuses one array, so the wrapper adds no more than one O(6 N) copy per evaluation.
/// </summary>
internal sealed class MathNetPeer
{
    private readonly ParticleWorld _system;
    private readonly double[] _input;
    private readonly MathNetVector _inputVector;
    private readonly Func<double, MathNetVector, MathNetVector> _derivative;

    public MathNetPeer(ParticleWorld system)
    {
        _system = system;
        _input = new double[system.Dimension];
        _inputVector = MathNetVector.Build.Dense(_input); // wraps _input, no copy
        _derivative = Derivative;
    }

    /// <summary>Integrates <paramref name="steps"/> RK4 steps of <paramref name="dt"/> from <paramref name="initial"/>; returns the last state.</summary>
    public MathNetVector Solve(MathNetVector initial, double dt, int steps)
    {
        // FourthOrder takes the number of output points N: N - 1 steps of (end - start) / (N - 1).
        var trajectory = RungeKutta.FourthOrder(initial, 0.0, steps * dt, steps + 1, _derivative);
        return trajectory[steps];
    }

    private MathNetVector Derivative(double time, MathNetVector y)
    {
        y.CopyTo(_inputVector);
        var result = new double[_input.Length];
        _system.Evaluate(time, _input, result);
        return MathNetVector.Build.Dense(result);
    }
}
