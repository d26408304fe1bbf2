using System;
using System.IO;
using System.Linq;
using ParticlePhysics.Tests.Engine;

namespace ParticlePhysics.Tests.Demo;

/// <summary>
/// <c>--profile</c>: after the run, standard error holds each stage's time and the counts per step; standard output is
/// the run's, bit for bit (profiling changes no result); a plain ODE, which has no stages, refuses the option.
/// </summary>
public sealed class DemoProfileTests
{
    [Fact]
    public void A_profiled_run_prints_the_stages_and_the_counts_per_step_and_the_same_rows()
    {
        var plain = DemoProcess.Run("pendulum", "--duration", "0.5", "--format", "csv");
        var profiled = DemoProcess.Run("pendulum", "--duration", "0.5", "--format", "csv", "--profile");

        Assert.Equal(0, profiled.ExitCode);
        Assert.Equal(plain.Output, profiled.Output);
        Assert.Equal(string.Empty, plain.Error);
        var lines = profiled.ErrorLines;
        Assert.StartsWith("profile of 500 steps (wall clock;", lines[0], StringComparison.Ordinal);
        foreach (var stage in new[] { "integration", "forces", "constraints", "contacts", "  broad phase", "step" })
        {
            Assert.Contains(lines, l => l.StartsWith(stage + " ", StringComparison.Ordinal));
        }

        // rk4: four evaluations per step, in each of which the rod adds its forces, then one Resolve.
        Assert.Equal(
            "per step: force evaluations 4, Jacobian products 0, substeps 0, constraint-set calls 5, contact-set calls 0, contact pairs 0, contacts 0",
            lines[^1]);
        var step = lines.Single(l => l.StartsWith("step ", StringComparison.Ordinal));
        Assert.EndsWith("100.0 %", step, StringComparison.Ordinal);
    }

    [Fact]
    public void A_profiled_scene_under_xpbd_counts_its_substeps()
    {
        var scene = Path.Combine(ReadmeExamplesTests.RepositoryRoot(), "samples", "scenes", "newtons-cradle.json");

        var result = DemoProcess.Run("scene", scene, "--integrator", "xpbd", "--substeps", "4", "--duration", "0.05", "--format", "csv", "--profile");

        Assert.Equal(0, result.ExitCode);
        Assert.StartsWith("per step: force evaluations 4, Jacobian products 0, substeps 4, ", result.ErrorLines[^1], StringComparison.Ordinal);
    }

    [Fact]
    public void A_plain_ode_has_no_stages_to_profile()
    {
        var result = DemoProcess.Run("scalar-ode", "--profile");

        Assert.Equal(2, result.ExitCode);
        Assert.Equal("error: unknown option '--profile' for scalar-ode; run 'scalar-ode --help' to list the options.", result.ErrorLines.Single());
    }
}
