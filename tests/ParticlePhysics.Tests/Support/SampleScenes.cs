using ParticlePhysics.Integrators;
using ParticlePhysics.Scenes;
using ParticlePhysics.Tests.Engine;

namespace ParticlePhysics.Tests.Support;

/// <summary>The repository's sample scenes, run as the scene command runs them, for the tests' golden hashes.</summary>
internal static class SampleScenes
{
    /// <summary>The bit hash of <c>samples/scenes/<paramref name="file"/></c>'s state after <paramref name="steps"/> steps.</summary>
    public static string BitHashAfter(string file, int steps)
    {
        var scene = Scene.Load(System.IO.Path.Combine(ReadmeExamplesTests.RepositoryRoot(), "samples", "scenes", file));
        var world = scene.Build();
        var stepper = IntegratorCatalog.Create(scene.Settings.Integrator, substeps: scene.Settings.Substeps);
        for (var s = 0; s < steps; s++)
        {
            world.Step(stepper, scene.Settings.TimeStep);
        }

        return StateMetrics.BitHash(world.State);
    }
}
