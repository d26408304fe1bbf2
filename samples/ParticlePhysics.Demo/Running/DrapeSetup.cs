using System;
using System.Collections.Generic;
using System.Linq;
using ParticlePhysics.Contacts;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Running;

/// <summary>
/// The drape's rows: the cloth's, plus <c>sphere_gap</c> (the smallest distance of a particle's surface to the sphere's:
/// negative inside) and <c>middle_y</c>; its summary: the deepest any particle went into the sphere over the run.
/// </summary>
internal sealed class DrapeSetup : ClothSetup
{
    private readonly DrapeScenario _scenario;
    private readonly Func<Recorder?> _latest;

    public DrapeSetup(string name, DrapeScenario scenario, int particlesPerSide)
        : this(name, scenario, particlesPerSide, new Recorder[1])
    {
    }

    private DrapeSetup(string name, DrapeScenario scenario, int particlesPerSide, Recorder[] latest)
        : base(name, scenario.Build, particlesPerSide, DrapeColumns(particlesPerSide), () => latest[0] = new Recorder())
    {
        _scenario = scenario;
        _latest = () => latest[0];
    }

    public override IReadOnlyList<string> SummaryDetails => new[]
    {
        $"deepest into the sphere over the run: {Numbers.Error(Math.Max(0, -(_latest()?.Deepest ?? 0)))} m (at most 1e-6 m allowed); "
            + $"the sphere's top is at y = {Numbers.Brief(_scenario.SphereY + _scenario.SphereRadius)} m, the middle particle rests at y = top + r "
            + $"= {Numbers.Brief(_scenario.SphereY + _scenario.SphereRadius + _scenario.Radius)} m",
    };

    private static ExtraColumn[] DrapeColumns(int n) => new[]
    {
        new ExtraColumn("sphere_gap", run => Gap(run.System)),
        new ExtraColumn("middle_y", run => run.System.GetPosition(((n / 2) * n) + (n / 2)).Y),
    };

    /// <summary>The smallest gap of a particle's surface to the sphere's, negative inside.</summary>
    private static double Gap(ParticleWorld world)
    {
        var sphere = world.Constraints.OfType<ContactSet>().Single().Obstacles[0];
        var gap = double.PositiveInfinity;
        for (var i = 0; i < world.Count; i++)
        {
            gap = Math.Min(gap, sphere.SignedDistance(world.GetPosition(i), out _) - world.GetRadius(i));
        }

        return gap;
    }

    /// <summary>One run's deepest gap over every step.</summary>
    private sealed class Recorder : IStepObserver
    {
        public double Deepest { get; private set; } = double.PositiveInfinity;

        public void AfterStep(ParticleWorld world) => Deepest = Math.Min(Deepest, Gap(world));
    }
}
