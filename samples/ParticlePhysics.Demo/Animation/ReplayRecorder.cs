using System;
using System.Collections.Generic;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Animation;

/// <summary>
/// Records a particle run for a replay: the positions at the display rate (a frame every 1/60 s of simulated time,
/// fewer when the particles are many enough that the frames would pass <see cref="MaxFrameBytes"/>), in single
/// precision, plus the run's few table values at each frame. The page interpolates between frames, so a coarser
/// recording still plays smoothly. Frames are the output rows of their steps, so their time is step * dt. With
/// <c>--profile</c> each frame also keeps the mean time per step of each stage over the steps since the frame before.
/// </summary>
internal sealed class ReplayRecorder : IRunObserver
{
    /// <summary>The frame rate of the recording at most, in frames per simulated second.</summary>
    public const double FramesPerSecond = 60;

    /// <summary>The most bytes of positions a recording keeps (4 bytes per coordinate); the frame rate drops to stay below.</summary>
    public const long MaxFrameBytes = 32L << 20;

    private readonly RunPlan _plan;
    private readonly int _count;
    private readonly int[] _valueColumns;
    private readonly double _stepsPerFrame;
    private readonly List<float> _positions = new();
    private readonly List<double> _times = new();
    private readonly List<double> _values = new();
    private readonly StageTimings? _timings;
    private readonly List<double> _stageTimes = new();
    private StepProfile _lastTotal;
    private int _lastSteps;
    private int _lastStep = -1;
    private long _nextFrame;

    /// <param name="setup">The particle scenario or scene: rows hold x{i}, y{i}, z{i} at 1 + 6 i.</param>
    /// <param name="particleCount">Its number of particles.</param>
    /// <param name="plan">The run.</param>
    /// <param name="timings">The run's stage timings (<c>--profile</c>), read at each frame, or null.</param>
    public ReplayRecorder(ScenarioSetup setup, int particleCount, RunPlan plan, StageTimings? timings = null)
    {
        _plan = plan;
        _timings = timings;
        _count = particleCount;
        ValueNames = Array.FindAll(ToArray(setup.TableColumns), c => c != "t");
        _valueColumns = Array.ConvertAll(ValueNames, setup.IndexOf);
        var bytesPerFrame = 12.0 * Math.Max(1, _count);
        var frames = Math.Min((plan.EndTime * FramesPerSecond) + 1, MaxFrameBytes / bytesPerFrame);
        var interval = Math.Max(plan.EndTime / Math.Max(1, frames - 1), 1.0 / FramesPerSecond);
        _stepsPerFrame = Math.Max(1, interval / plan.Dt);
    }

    /// <summary>The number of particles per frame.</summary>
    public int ParticleCount => _count;

    /// <summary>The names of the values kept at each frame (the table's columns but t).</summary>
    public string[] ValueNames { get; }

    /// <summary>The number of frames recorded.</summary>
    public int FrameCount => _times.Count;

    /// <summary>The time of each frame, step * dt.</summary>
    public IReadOnlyList<double> Times => _times;

    /// <summary>x, y, z of each particle, frame after frame, in single precision.</summary>
    public IReadOnlyList<float> Positions => _positions;

    /// <summary>The <see cref="ValueNames"/> of each frame, frame after frame.</summary>
    public IReadOnlyList<double> Values => _values;

    /// <summary>The stages whose times <see cref="StageTimes"/> holds, in its order.</summary>
    public static readonly string[] StageNames = { "integration", "forces", "constraints", "contacts" };

    /// <summary>
    /// With <c>--profile</c>: each stage's mean time per step in seconds (<see cref="StageNames"/>), frame after frame,
    /// over the steps since the frame before (0 for a frame with none, such as the first); null without.
    /// </summary>
    public IReadOnlyList<double>? StageTimes => _timings is null ? null : _stageTimes;

    /// <summary>How the run ended, once it has.</summary>
    public RunOutcome? Outcome { get; private set; }

    public bool Wants(int step)
    {
        // Frame k is at step round(k * stepsPerFrame): on the display-rate grid, or every step when dt is coarser.
        if (step < Math.Round(_nextFrame * _stepsPerFrame) && step != _plan.Steps)
        {
            return false;
        }

        while (Math.Round(_nextFrame * _stepsPerFrame) <= step)
        {
            _nextFrame++;
        }

        return true;
    }

    public void Add(int step, double[] row) => Record(step, row);

    public void Finish(RunOutcome outcome)
    {
        // A run cut short (diverged, interrupted) ends on its last good state, which may fall between frames.
        if (outcome.FinalStep != _lastStep)
        {
            Record(outcome.FinalStep, outcome.FinalRow);
        }

        Outcome = outcome;
    }

    private void Record(int step, double[] row)
    {
        _lastStep = step;
        _times.Add(step * _plan.Dt);
        for (var i = 0; i < _count; i++)
        {
            for (var c = 0; c < 3; c++)
            {
                _positions.Add((float)row[1 + (6 * i) + c]);
            }
        }

        foreach (var column in _valueColumns)
        {
            _values.Add(row[column]);
        }

        if (_timings is not null)
        {
            RecordStageTimes(_timings);
        }
    }

    private void RecordStageTimes(StageTimings timings)
    {
        var total = timings.Total;
        var steps = timings.Steps - _lastSteps;
        var scale = steps > 0 ? 1.0 / steps : 0.0;
        _stageTimes.Add((total.IntegrationSeconds - _lastTotal.IntegrationSeconds) * scale);
        _stageTimes.Add((total.ForceSeconds - _lastTotal.ForceSeconds) * scale);
        _stageTimes.Add((total.ConstraintSeconds - _lastTotal.ConstraintSeconds) * scale);
        _stageTimes.Add((total.ContactSeconds - _lastTotal.ContactSeconds) * scale);
        _lastTotal = total;
        _lastSteps = timings.Steps;
    }

    private static string[] ToArray(IReadOnlyList<string> list)
    {
        var array = new string[list.Count];
        for (var i = 0; i < array.Length; i++)
        {
            array[i] = list[i];
        }

        return array;
    }
}
