using System;
using System.Collections.Generic;
using System.Globalization;
using System.IO;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// The bouncing ball's rows, and the summary of its bounces: each impact time (as the contact set resolved it) and
/// apex height (the top of the parabola through the state before it) against t1 + 2 u1 (e + ... + e^(n-1)) / g and
/// R + e^(2n) (h - R).
/// </summary>
internal sealed class BouncingBallSetup : ParticleSetup
{
    /// <summary>How many bounces the table summary lists.</summary>
    public const int ListedBounces = 6;

    private readonly BouncingBallScenario _scenario;
    private readonly Recorders _recorders;

    public BouncingBallSetup(string name, BouncingBallScenario scenario)
        : this(name, scenario, new Recorders(scenario))
    {
    }

    private BouncingBallSetup(string name, BouncingBallScenario scenario, Recorders recorders)
        : base(name, scenario.Build, 1, scenario.HasExactSolution ? scenario : null, observer: recorders.Create)
    {
        _scenario = scenario;
        _recorders = recorders;
    }

    /// <inheritdoc />
    public override double? MotionEnds => double.IsFinite(_scenario.RestTime) && _scenario.Friction == 0 && _scenario.Vx0 == 0 ? _scenario.RestTime : null;

    public override IReadOnlyList<string> SummaryDetails
    {
        get
        {
            var exact = _scenario.HasExactSolution;
            var run = _recorders.Latest ?? new Recorder(_scenario);
            var impacts = run.Impacts;
            var apexes = run.Apexes;
            var restTime = run.RestTime;
            var table = new TextTable(">bounce", ">impact t (s)", ">exact t (s)", ">apex y (m)", ">exact apex (m)", ">apex rel. error");
            var count = Math.Min(ListedBounces, Math.Max(impacts.Count, apexes.Count));
            for (var n = 1; n <= count; n++)
            {
                var impact = n <= impacts.Count ? impacts[n - 1] : double.NaN;
                var apex = n <= apexes.Count ? apexes[n - 1] : double.NaN;
                table.Add(
                    n.ToString(CultureInfo.InvariantCulture),
                    Numbers.Brief(impact),
                    exact ? Numbers.Brief(_scenario.ImpactTime(n)) : "n/a",
                    Numbers.Brief(apex),
                    exact ? Numbers.Brief(_scenario.ApexHeight(n)) : "n/a",
                    exact ? Numbers.Error(Math.Abs(apex - _scenario.ApexHeight(n)) / _scenario.ApexHeight(n)) : "n/a");
            }

            var lines = new List<string>
            {
                exact
                    ? $"bounces against the exact ones (apex R + e^(2n) (h - R), impact t1 + 2 u1 (e + ... + e^(n-1)) / g), the first {count}:"
                    : $"bounces (no exact solution with drag), the first {count}:",
            };
            using (var text = new StringWriter(CultureInfo.InvariantCulture))
            {
                table.Write(text);
                lines.AddRange(text.ToString().TrimEnd().Split('\n'));
            }

            lines.Add(double.IsNaN(restTime)
                ? $"{impacts.Count} bounces; still bouncing at the end"
                : $"{impacts.Count} bounces; at rest from t = {Numbers.Brief(restTime)} s"
                    + (exact && _scenario.Restitution < 1
                        ? $" (exact T = t1 (1 + e) / (1 - e) = {Numbers.Brief(_scenario.RestTime)} s; rebounds below {Numbers.Brief(ContactSet.DefaultRestingSpeed)} m/s rest)"
                        : string.Empty));
            return lines;
        }
    }

    /// <summary>Makes each run's recorder and keeps the latest, whose bounces the summary lists.</summary>
    private sealed class Recorders
    {
        private readonly BouncingBallScenario _scenario;

        public Recorders(BouncingBallScenario scenario)
        {
            _scenario = scenario;
        }

        public Recorder? Latest { get; private set; }

        public IStepObserver Create() => Latest = new Recorder(_scenario);
    }

    /// <summary>One run's bounces: the impact times the contact set reports, and each apex.</summary>
    private sealed class Recorder : IStepObserver
    {
        private readonly BouncingBallScenario _scenario;
        private double _y;
        private double _vy;

        public Recorder(BouncingBallScenario scenario)
        {
            _scenario = scenario;
            _y = scenario.Height;
        }

        public List<double> Impacts { get; } = new();

        public List<double> Apexes { get; } = new();

        public double RestTime { get; private set; } = double.NaN;

        public void AfterStep(ParticleWorld world)
        {
            var contacts = world.Constraints.OfType<ContactSet>().Single();
            var bounced = false;
            foreach (var impact in contacts.Impacts)
            {
                if (!impact.Resting)
                {
                    Impacts.Add(impact.Time);
                    bounced = true;
                }
                else if (double.IsNaN(RestTime))
                {
                    RestTime = impact.Time;
                }
            }

            var velocity = world.GetVelocity(0).Y;
            if (!bounced && _vy <= 0 && velocity > 0 && _scenario.Gravity > 0)
            {
                // A bounce the contact set did not log (xpbd logs only its last substep): its time from the arc after
                // it, y - R = vy tau + g tau^2 / 2 (tau: the time since the impact).
                var g = _scenario.Gravity;
                var tau = (-velocity + Math.Sqrt((velocity * velocity) + (2 * g * Math.Max(0, world.GetPosition(0).Y - _scenario.Radius)))) / g;
                Impacts.Add(world.Time - tau);
            }

            if (_vy > 0 && velocity <= 0 && contacts.ImpactCount == 0 && _scenario.Gravity > 0)
            {
                // The top of the flight within this step: exact for a ballistic arc through the state before it.
                Apexes.Add(_y + (_vy * _vy / (2 * _scenario.Gravity)));
            }

            _y = world.GetPosition(0).Y;
            _vy = velocity;
        }
    }
}
