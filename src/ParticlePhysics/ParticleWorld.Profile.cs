using System;
using System.Diagnostics;
using ParticlePhysics.Internal;

namespace ParticlePhysics;

// The step's profile (StepProfile): Stopwatch timestamps around what the world calls, added up per stage while a
// profiled step runs, published when it commits. Two timestamps per call at most, never one per particle.
public sealed partial class ParticleWorld
{
    private bool _profiling;
    private StepProfile _lastProfile;

    // The step in progress: Stopwatch ticks per stage and the counts, cleared when a profiled step starts.
    private long _forceTicks;
    private long _constraintTicks;
    private long _contactTicks;
    private int _forceEvaluations;
    private int _jacobianProducts;
    private int _substeps;
    private int _constraintCalls;
    private int _contactCalls;

    /// <summary>
    /// Whether each step measures what its stages cost (<see cref="LastStepProfile"/>); off by default. On, a step
    /// reads the clock twice per force evaluation, Jacobian product and constraint-set call (never per particle),
    /// allocates nothing, and computes the same bits as with it off. Set it between steps: like every change to the
    /// world, setting it from inside the world's own step throws.
    /// </summary>
    public bool Profiling
    {
        get => _profiling;
        set
        {
            ThrowIfStepping();
            _profiling = value;
        }
    }

    /// <summary>
    /// What the last committed step cost, stage by stage, when it was taken with <see cref="Profiling"/> on (all zero
    /// after a step taken with it off, and before any step). A step that fails leaves it as it was.
    /// </summary>
    public StepProfile LastStepProfile => _lastProfile;

    /// <summary>A profiled step starts: the stages' sums cleared, and the contact sets told to time their broad phase.</summary>
    private void BeginProfile()
    {
        _forceTicks = 0;
        _constraintTicks = 0;
        _contactTicks = 0;
        _forceEvaluations = 0;
        _jacobianProducts = 0;
        _substeps = 0;
        _constraintCalls = 0;
        _contactCalls = 0;
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            (_constraintSets[c] as IContactStage)?.BeginProfile();
        }
    }

    /// <summary>
    /// A profiled step ends (its stages over, committed or not): the contact sets stop timing, and a committed step's
    /// profile becomes <see cref="LastStepProfile"/>.
    /// </summary>
    private void EndProfile(bool committed, long started)
    {
        long broadPhaseTicks = 0;
        int pairs = 0, contacts = 0;
        for (var c = 0; c < _constraintSets.Count; c++)
        {
            if (_constraintSets[c] is IContactStage stage)
            {
                stage.EndProfile(out var setTicks, out var setPairs, out var setContacts);
                broadPhaseTicks += setTicks;
                pairs += setPairs;
                contacts += setContacts;
            }
        }

        if (committed)
        {
            var seconds = 1.0 / Stopwatch.Frequency;
            _lastProfile = new StepProfile(
                (Stopwatch.GetTimestamp() - started) * seconds,
                _forceTicks * seconds,
                _constraintTicks * seconds,
                _contactTicks * seconds,
                broadPhaseTicks * seconds,
                _forceEvaluations,
                _jacobianProducts,
                _substeps,
                _constraintCalls,
                _contactCalls,
                pairs,
                contacts);
        }
    }

    /// <summary>The clock now when profiling, else 0 (and no clock read).</summary>
    private long ProfileStart() => _profiling ? Stopwatch.GetTimestamp() : 0;

    /// <summary>Adds the time since <paramref name="started"/> to the forces' stage.</summary>
    private void ProfileForces(long started)
    {
        if (_profiling)
        {
            _forceTicks += Stopwatch.GetTimestamp() - started;
        }
    }

    /// <summary>
    /// Adds the time since <paramref name="started"/> and one evaluation to the forces' stage; returns the clock now
    /// (0 when not profiling), where the constraint forces' time starts.
    /// </summary>
    private long ProfileEvaluation(long started)
    {
        if (!_profiling)
        {
            return 0;
        }

        var now = Stopwatch.GetTimestamp();
        _forceTicks += now - started;
        _forceEvaluations++;
        return now;
    }

    /// <summary>Adds the time since <paramref name="started"/> and one Jacobian product to the forces' stage.</summary>
    private void ProfileProduct(long started)
    {
        if (_profiling)
        {
            _forceTicks += Stopwatch.GetTimestamp() - started;
            _jacobianProducts++;
        }
    }

    /// <summary>Adds the time since <paramref name="started"/> and <paramref name="calls"/> calls to the constraint stage.</summary>
    private void ProfileConstraintForces(long started, int calls)
    {
        if (_profiling)
        {
            _constraintTicks += Stopwatch.GetTimestamp() - started;
            _constraintCalls += calls;
        }
    }

    /// <summary>
    /// Adds the time since <paramref name="started"/> and one call to the stage of <paramref name="set"/>: contacts when
    /// it is a contact stage (<see cref="IContactStage"/>), constraints otherwise.
    /// </summary>
    private void ProfileSet(IConstraintSet set, long started)
    {
        if (!_profiling)
        {
            return;
        }

        var ticks = Stopwatch.GetTimestamp() - started;
        if (set is IContactStage)
        {
            _contactTicks += ticks;
            _contactCalls++;
        }
        else
        {
            _constraintTicks += ticks;
            _constraintCalls++;
        }
    }
}
