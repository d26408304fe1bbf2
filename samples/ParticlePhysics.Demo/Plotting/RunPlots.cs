using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>Picks the chart that suits a run: mesh snapshots for the cloth, the trajectory against the exact solution otherwise.</summary>
internal static class RunPlots
{
    public static IRunPlot For(ScenarioSetup setup, RunPlan plan) =>
        setup is ClothSetup cloth ? new ClothSnapshotPlot(cloth, plan) : new TrajectoryPlot(setup, plan);
}
