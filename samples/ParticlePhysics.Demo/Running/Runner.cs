using System;
using System.Collections.Generic;
using System.Threading;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// The time loop, kept out of the integrators (as Boost.Odeint keeps its integrate loop apart from its steppers):
/// steps a fresh simulation with a constant dt and hands the rows of step 0, every N-th step and the last step to
/// an observer. Times are step * dt, never a running sum, so t = 0.3 prints as 0.3 and not 0.30000000000000004.
/// </summary>
internal static class Runner
{
    /// <summary>Runs <paramref name="setup"/> as <paramref name="plan"/> says; stops at the first diverged step.</summary>
    /// <param name="setup">The scenario.</param>
    /// <param name="plan">The integrator, dt, steps and output stride.</param>
    /// <param name="onRow">Receives each output row (the array is reused: copy it to keep it), or null.</param>
    /// <param name="progress">Told about each step, or null.</param>
    /// <param name="observers">Observers that pick their own steps (a plot's snapshots, an animation's frames), or null.</param>
    /// <param name="cancellation">Stops the run between two steps (Ctrl-C): the outcome is then marked interrupted.</param>
    /// <param name="timings">Adds up each step's stage timings (the world profiles its steps), or null.</param>
    public static RunOutcome Run(
        ScenarioSetup setup,
        RunPlan plan,
        Action<double[]>? onRow,
        ProgressReporter? progress = null,
        IReadOnlyList<IRunObserver>? observers = null,
        CancellationToken cancellation = default,
        StageTimings? timings = null)
    {
        observers ??= Array.Empty<IRunObserver>();
        var simulation = setup.TakeSimulation();
        if (timings is not null)
        {
            StageTimings.Start(simulation);
        }

        var integrator = IntegratorCatalog.Create(plan.Integrator, plan.Tolerance, plan.Substeps);
        var row = new double[setup.Columns.Count];
        var wanted = new bool[observers.Count];
        var lastRowStep = -1;
        void Emit(int step)
        {
            var output = plan.IsOutputStep(step);
            var tapped = false;
            for (var i = 0; i < observers.Count; i++)
            {
                wanted[i] = observers[i].Wants(step);
                tapped |= wanted[i];
            }

            if (!output && !tapped)
            {
                return;
            }

            setup.FillRow(simulation, step * plan.Dt, row);
            lastRowStep = step;
            if (output)
            {
                onRow?.Invoke(row);
            }

            for (var i = 0; i < observers.Count; i++)
            {
                if (wanted[i])
                {
                    observers[i].Add(step, row);
                }
            }
        }

        RunOutcome Finish(RunOutcome outcome)
        {
            progress?.Clear();
            foreach (var observer in observers)
            {
                observer.Finish(outcome);
            }

            return outcome;
        }

        Emit(0);
        for (var step = 1; step <= plan.Steps; step++)
        {
            if (cancellation.IsCancellationRequested)
            {
                var done = step - 1;
                if (lastRowStep != done)
                {
                    setup.FillRow(simulation, done * plan.Dt, row);
                }

                return Finish(new RunOutcome(row, done, done * plan.Dt, setup.ErrorAt(simulation, done * plan.Dt), null, Interrupted: true));
            }

            try
            {
                simulation.Step(integrator, plan.Dt);
            }
            catch (Exception exception) when (exception is SimulationDivergedException or SolverNotConvergedException)
            {
                // The step failed (diverged, or rk45 hit a bound of its work): the simulation is at its last good state.
                var good = step - 1;
                if (lastRowStep != good)
                {
                    setup.FillRow(simulation, good * plan.Dt, row);
                }

                return Finish(new RunOutcome(
                    row, good, good * plan.Dt, setup.ErrorAt(simulation, good * plan.Dt), new Divergence(step, step * plan.Dt, exception)));
            }

            timings?.AfterStep(simulation);
            Emit(step);

            progress?.Report(step, plan.Steps);
        }

        return Finish(new RunOutcome(row, plan.Steps, plan.EndTime, setup.ErrorAt(simulation, plan.EndTime), null));
    }
}
