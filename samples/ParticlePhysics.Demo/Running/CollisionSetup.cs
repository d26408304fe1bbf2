using System;
using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Running;

/// <summary>The collision's rows (exact columns along x), and its summary: the contact time and the velocities after, against the exact ones.</summary>
internal sealed class CollisionSetup : ParticleSetup
{
    private readonly CollisionScenario _scenario;
    private readonly Func<Recorder?> _latest;

    public CollisionSetup(string name, CollisionScenario scenario)
        : this(name, scenario, new Recorder[1])
    {
    }

    private CollisionSetup(string name, CollisionScenario scenario, Recorder[] latest)
        : base(name, scenario.Build, 2, scenario, observer: () => latest[0] = new Recorder(scenario), exactAxis: 0)
    {
        _scenario = scenario;
        _latest = () => latest[0];
    }

    public override string PlotAxisLabel => "position x (m)";

    public override IReadOnlyList<string> SummaryDetails
    {
        get
        {
            var run = _latest() ?? new Recorder(_scenario);
            return new[]
            {
                double.IsNaN(run.Contact)
                    ? $"no contact (exact: {(double.IsInfinity(_scenario.ContactTime) ? "none, v1 <= v2" : $"at t* = {Numbers.Brief(_scenario.ContactTime)} s")})"
                    : $"contact at t = {Numbers.Brief(run.Contact)} s (exact t* = (2 - 2 r) / (v1 - v2) = {Numbers.Brief(_scenario.ContactTime)} s); "
                        + $"leaving with v1' = {Numbers.Brief(_scenario.FinalVelocity1)}, v2' = {Numbers.Brief(_scenario.FinalVelocity2)} m/s exact; "
                        + $"momentum changed by {Numbers.Error(Math.Abs(run.FinalMomentum - run.Momentum))} kg m/s",
            };
        }
    }

    /// <summary>One run's first contact time and its momentum along x (gravity adds momentum along y only).</summary>
    private sealed class Recorder : IStepObserver
    {
        public Recorder(CollisionScenario scenario)
        {
            Momentum = (scenario.Mass1 * scenario.Velocity1) + (scenario.Mass2 * scenario.Velocity2);
            FinalMomentum = Momentum;
        }

        public double Contact { get; private set; } = double.NaN;

        public double Momentum { get; }

        public double FinalMomentum { get; private set; }

        public void AfterStep(ParticleWorld world)
        {
            foreach (var impact in world.Constraints.OfType<ContactSet>().Single().Impacts)
            {
                Contact = double.IsNaN(Contact) ? impact.Time : Contact;
            }

            FinalMomentum = world.TotalMomentum().X;
        }
    }
}
