using System;
using System.Globalization;
using ParticlePhysics.Numerics;

namespace ParticlePhysics;

// The step: the integrator, then the constraint stage, then the commit, all or nothing (docs/architecture.md).
public sealed partial class ParticleWorld
{
    private bool _stepping;
    private bool _sleepActive; // this step may wake and put to sleep (BeginSleep)
    private int _frameDepth; // open FixedTimestepDriver frames: their steps leave the constraint sets' bracket to them

    /// <summary>
    /// Advances the system by one step of <paramref name="dt"/> seconds with <paramref name="integrator"/>, in stages:
    /// the integrator advances the state under the forces into a scratch buffer; the constraint stage corrects it
    /// (<see cref="IConstraintSet.Resolve"/>, every set in order), except after a position-based integrator
    /// (<see cref="IPositionBasedIntegrator"/>), which has projected every set in its substeps; the result is committed
    /// only if it is finite and its velocities are within <see cref="DivergenceLimit"/>. If any stage throws, the world
    /// is left exactly as it was, and so is an integrator that carries state (<see cref="IStatefulIntegrator"/>): it is
    /// told to commit the state of a committed step and to discard that of a failed one, so a retry takes the same step
    /// as one from a restored snapshot.
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">
    /// <paramref name="dt"/> is not a positive finite number, or <see cref="Time"/> + <paramref name="dt"/> is not finite.
    /// </exception>
    /// <exception cref="SimulationDivergedException">
    /// The step produced a value that is not finite, or a velocity beyond <see cref="DivergenceLimit"/>; the system
    /// stays at its last good state and time.
    /// </exception>
    /// <exception cref="InvalidOperationException">
    /// Called from inside this world's own step (a force, a pair filter or a constraint set stepping the world it
    /// belongs to): the nested step would swap the buffers the outer one is writing into. The outer step then fails,
    /// and the world is left as it was.
    /// </exception>
    public void Step(IIntegrator integrator, double dt)
    {
        ThrowIfStepping();
        Guard.NotNull(integrator, nameof(integrator));
        Guard.PositiveFinite(dt, nameof(dt));
        Guard.FiniteEndTime(_time, dt);
        var started = ProfileStart();
        Compact();
        var dimension = 6 * _count;
        if (_next.Length != dimension)
        {
            _next = new double[dimension];
        }

        var current = _state.AsSpan(0, dimension);
        var stateful = integrator as IStatefulIntegrator;
        var committed = false;
        var bracket = _frameDepth == 0;
        if (bracket)
        {
            BeginConstraintSets();
        }

        var profiling = _profiling;
        if (profiling)
        {
            BeginProfile();
        }

        _sleepActive = BeginSleep(integrator is IPositionBasedIntegrator);
        _stepping = true;
        try
        {
            integrator.Step(this, _time, current, _next, dt);
            if (integrator is not IPositionBasedIntegrator)
            {
                ResolveConstraints(current, dt, integrator is IKickDriftIntegrator);
            }

            _stepping = false;
            CheckDiverged(dt);

            // Commit by swapping the buffers (the spans handed out before the step are documented as stale after it).
            (_state, _next) = (_next, _state);
            _time += dt;
            committed = true;
            if (_sleepActive)
            {
                UpdateSleep(dt);
            }
        }
        finally
        {
            _stepping = false;

            // The integrator's own state follows the world's: kept with a committed step, forgotten with a failed one.
            if (committed)
            {
                stateful?.CommitStep();
            }
            else
            {
                stateful?.DiscardStep();
                UndoWakes();
            }

            _recordWakes = false;
            _sleepActive = false;

            if (bracket)
            {
                EndConstraintSets(committed);
            }

            if (profiling)
            {
                EndProfile(committed, started);
            }
            else if (committed)
            {
                _lastProfile = default;
            }
        }
    }

    /// <summary>
    /// Opens one all-or-nothing bracket around several steps (a <see cref="Driver.FixedTimestepDriver"/> frame): the
    /// stateful constraint sets (<see cref="IStatefulConstraintSet"/>) keep aside what they show now, and the steps
    /// inside leave them to <see cref="EndFrame"/>.
    /// </summary>
    internal void BeginFrame()
    {
        if (_frameDepth++ == 0)
        {
            BeginConstraintSets();
            SaveSleep();
        }
    }

    /// <summary>Closes the bracket of <see cref="BeginFrame"/>: the sets keep the frame's result, or show again what they showed before it.</summary>
    internal void EndFrame(bool committed)
    {
        if (--_frameDepth == 0)
        {
            EndConstraintSets(committed);
            if (!committed)
            {
                RestoreSleep();
            }
        }
    }

    private void BeginConstraintSets()
    {
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            (_constraintSets[c] as IStatefulConstraintSet)?.BeginStep();
        }
    }

    private void EndConstraintSets(bool committed)
    {
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            if (_constraintSets[c] is IStatefulConstraintSet set)
            {
                if (committed)
                {
                    set.CommitStep();
                }
                else
                {
                    set.DiscardStep();
                }
            }
        }
    }

    /// <summary>
    /// The commit's check of the end state in the scratch buffer: every position finite, every velocity component
    /// within <see cref="DivergenceLimit"/> (one comparison per value; NaN fails it).
    /// </summary>
    private void CheckDiverged(double dt)
    {
        var n = 3 * _count;
        var bad = DoubleChecks.FirstBeyond(_next.AsSpan(0, n), double.MaxValue);
        var velocity = false;
        if (bad < 0)
        {
            bad = DoubleChecks.FirstBeyond(_next.AsSpan(n, n), _divergenceLimit);
            velocity = bad >= 0;
        }

        if (bad < 0)
        {
            return;
        }

        var value = velocity ? _next[n + bad] : _next[bad];
        var particle = bad / 3;
        var axis = "xyz"[bad % 3];
        var cause = DoubleChecks.IsFinite(value)
            ? string.Format(
                CultureInfo.InvariantCulture,
                "particle {0} reached v{1} = {2:R} m/s, beyond the divergence limit {3:R} m/s",
                particle,
                axis,
                value,
                _divergenceLimit)
            : string.Format(
                CultureInfo.InvariantCulture,
                "particle {0}'s {1} {2} is no longer finite ({3})",
                particle,
                velocity ? "velocity" : "position",
                velocity ? "v" + axis : axis.ToString(),
                value);
        throw new SimulationDivergedException(
            _time + dt, _time, velocity ? n + bad : bad, particle, value, _divergenceLimit, cause);
    }

    /// <summary>
    /// The constraint stage after a force-based step: every set corrects the end state in the scratch buffer, told
    /// whether the step was a kick and a drift (<see cref="ConstraintContext.KickDrift"/>).
    /// </summary>
    private void ResolveConstraints(Span<double> start, double dt, bool kickDrift)
    {
        if (_constraintSets.Count == 0)
        {
            return;
        }

        var n = 3 * _count;
        var end = _next.AsSpan(0, 2 * n);
        var context = new ConstraintContext(
            _time, dt, start.Slice(0, n), start.Slice(n, n), end.Slice(0, n), end.Slice(n, n), Masses, InverseMasses, Radii, Runner, kickDrift);
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            var set = _constraintSets[c];
            var started = ProfileStart();
            set.Resolve(in context);
            ProfileSet(set, started);
        }
    }

    /// <summary>
    /// Throws when called from inside this world's own step (by a force generator, a pair filter or a constraint set):
    /// every change to the world, a nested step of it, and its driver's frames and resets.
    /// </summary>
    internal void ThrowIfStepping()
    {
        if (_stepping)
        {
            throw new InvalidOperationException(
                "The world cannot be changed or stepped during its own step (from a force generator, a pair filter or "
                + "a constraint set): a step either commits whole or leaves the world as it was.");
        }
    }
}
