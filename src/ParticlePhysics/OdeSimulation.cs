using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics;

/// <summary>
/// The time loop for a plain <see cref="IOdeSystem"/> (such as the course's scalar example dy/dt = -2 y t):
/// it owns the state vector and its time, and commits a step only when its result is finite.
/// A <see cref="ParticleWorld"/> owns its state itself and has its own <see cref="ParticleWorld.Step"/>.
/// </summary>
public sealed class OdeSimulation
{
    private readonly double[] _state;
    private readonly double[] _next;
    private double _divergenceLimit = double.MaxValue;

    /// <summary>Starts a simulation of <paramref name="system"/> from <paramref name="initialState"/> at <paramref name="initialTime"/>.</summary>
    public OdeSimulation(IOdeSystem system, ReadOnlySpan<double> initialState, double initialTime = 0.0)
    {
        Guard.NotNull(system, nameof(system));
        if (initialState.Length != system.Dimension)
        {
            throw new ArgumentException(
                $"initialState must have the system's dimension {system.Dimension}; got {initialState.Length}.",
                nameof(initialState));
        }

        var bad = DoubleChecks.FirstNonFinite(initialState);
        if (bad >= 0)
        {
            throw new ArgumentException(
                $"initialState must be finite; component {bad} is {Guard.Format(initialState.ForReading()[bad])}.", nameof(initialState));
        }

        Guard.Finite(initialTime, nameof(initialTime));
        System = system;
        _state = initialState.ToArray();
        _next = new double[_state.Length];
        Time = initialTime;
    }

    /// <summary>The system being integrated.</summary>
    public IOdeSystem System { get; }

    /// <summary>The current time, in seconds.</summary>
    public double Time { get; private set; }

    /// <summary>The current state vector.</summary>
    public ReadOnlySpan<double> State => _state;

    /// <summary>
    /// The largest magnitude a state component may reach before a step counts as diverged. Default
    /// <see cref="double.MaxValue"/>: only NaN and infinity stop a plain ODE, whose values may be of any scale.
    /// </summary>
    public double DivergenceLimit
    {
        get => _divergenceLimit;
        set
        {
            Guard.PositiveFinite(value, nameof(DivergenceLimit));
            _divergenceLimit = value;
        }
    }

    /// <summary>Advances by one step of <paramref name="dt"/> with <paramref name="integrator"/>.</summary>
    /// <exception cref="ArgumentOutOfRangeException">
    /// <paramref name="dt"/> is not a positive finite number, or <see cref="Time"/> + <paramref name="dt"/> is not finite.
    /// </exception>
    /// <exception cref="SimulationDivergedException">
    /// The step's result is not finite (or beyond <see cref="DivergenceLimit"/>); the state is left as it was.
    /// </exception>
    public void Step(IIntegrator integrator, double dt)
    {
        Guard.NotNull(integrator, nameof(integrator));
        Guard.PositiveFinite(dt, nameof(dt));
        Guard.FiniteEndTime(Time, dt);
        var stateful = integrator as IStatefulIntegrator;
        var committed = false;
        try
        {
            integrator.Step(System, Time, _state, _next, dt);
            var bad = DoubleChecks.FirstBeyond(_next, _divergenceLimit);
            if (bad >= 0)
            {
                throw new SimulationDivergedException(Time + dt, Time, bad, -1, _next[bad], _divergenceLimit);
            }

            _next.AsSpan().CopyTo(_state);
            Time += dt;
            committed = true;
        }
        finally
        {
            // As in ParticleWorld.Step: a stateful integrator keeps the state of a committed step only.
            if (committed)
            {
                stateful?.CommitStep();
            }
            else
            {
                stateful?.DiscardStep();
            }
        }
    }
}
