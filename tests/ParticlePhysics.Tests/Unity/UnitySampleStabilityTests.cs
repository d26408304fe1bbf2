using System;
using System.Collections.Generic;
using System.Linq;
using System.Reflection;
using ParticlePhysics.Cloth;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Unity;

/// <summary>
/// The sample's Inspector defaults stay stable at every size its slider allows: 3 simulated seconds at 60 Hz from
/// rest, the solver converging at every step, no divergence, every particle near a pin. The even sizes run here, the
/// odd ones in <see cref="UnitySampleStabilityOddSizeTests"/>, so that the two halves run in parallel.
/// </summary>
public class UnitySampleStabilityTests
{
    private const int Frames = 180;

    /// <summary>The values of the sample's particlesPerSide slider ([Range] on the field) whose parity is <paramref name="parity"/>.</summary>
    public static IEnumerable<object[]> AllowedSizes(int parity)
    {
        using var player = new UnityPlayer();
        var range = player.SampleType.GetField("particlesPerSide")!.GetCustomAttributes()
            .Single(a => a.GetType().FullName == "UnityEngine.RangeAttribute");
        var min = (int)(float)range.GetType().GetField("min")!.GetValue(range)!;
        var max = (int)(float)range.GetType().GetField("max")!.GetValue(range)!;
        Assert.Equal((2, 64), (min, max));
        return Enumerable.Range(min, max - min + 1).Where(n => n % 2 == parity).Select(n => new object[] { n });
    }

    [Theory]
    [MemberData(nameof(AllowedSizes), 0)]
    public void The_defaults_stay_stable_for_three_seconds(int particlesPerSide) => RunThreeSeconds(particlesPerSide);

    internal static void RunThreeSeconds(int particlesPerSide)
    {
        using var player = new UnityPlayer(sample => sample.GetType().GetField("particlesPerSide")!.SetValue(sample, particlesPerSide));
        player.RunFrame(0f);
        var world = player.Cloth.System;
        var solver = (ImplicitEuler)player.Driver.Integrator;
        var side = (float)player.GetField("sideLength");
        var pins = new[] { world.GetPosition(player.Cloth.ParticleIndex(0, 0)), world.GetPosition(player.Cloth.ParticleIndex(0, particlesPerSide - 1)) };
        for (var frame = 0; frame < Frames; frame++)
        {
            player.RunFrame(1f / 60);
            Assert.True(player.Enabled, $"frame {frame}: {player.Errors}");
            Assert.True(solver.LastConverged, $"frame {frame}: the implicit solve stopped at residual {solver.LastResidual}");
        }

        Assert.Equal(Frames, player.Driver.StepCount);
        Assert.Equal(string.Empty, player.Errors);

        // Springs of finite stiffness stretch, but a sane cloth stays within three sides of a pin.
        for (var i = 0; i < world.Count; i++)
        {
            var p = world.GetPosition(i);
            var nearest = Math.Min((p - pins[0]).Length, (p - pins[1]).Length);
            Assert.True(nearest <= 3 * side, $"particle {i} is {nearest} m from the nearest pin");
        }
    }

    [Fact]
    public void The_samples_loose_solver_tolerance_moves_the_default_cloth_by_less_than_a_tenth_of_a_millimetre()
    {
        // The sample's cloth and steps, with its tolerance (1e-3) and with the default one (1e-6), for 10 s at 60 Hz.
        using var player = new UnityPlayer();
        player.RunFrame(0f);
        var tolerance = (double)player.SampleType.GetField("SolverTolerance")!.GetValue(null)!;
        Assert.Equal(1e-3, tolerance);
        var loose = player.Cloth.System;
        var looseSolver = (ImplicitEuler)player.Driver.Integrator;
        var n = (int)player.GetField("particlesPerSide");
        var builder = new ClothBuilder { Rows = n, Columns = n, Spacing = (double)(float)player.GetField("sideLength") / (n - 1), TotalMass = (float)player.GetField("totalMass") };
        builder.WithSprings((float)player.GetField("stiffness"), (float)player.GetField("damping"));
        var tight = builder.Build().System;
        var tightSolver = new ImplicitEuler();
        Assert.Equal(1e-6, tightSolver.Tolerance);
        Assert.Equal(loose.State.ToArray(), tight.State.ToArray());

        long looseIterations = 0, tightIterations = 0;
        var largest = 0.0;
        for (var step = 0; step < 600; step++)
        {
            loose.Step(looseSolver, 1.0 / 60);
            tight.Step(tightSolver, 1.0 / 60);
            looseIterations += looseSolver.LastIterations;
            tightIterations += tightSolver.LastIterations;
            for (var i = 0; i < loose.Count; i++)
            {
                largest = Math.Max(largest, (loose.GetPosition(i) - tight.GetPosition(i)).Length);
            }
        }

        Assert.True(largest < 1e-4, $"the tolerances differ by {largest} m");
        Assert.True(looseIterations < tightIterations, $"iterations: {looseIterations} at 1e-3, {tightIterations} at 1e-6");
    }
}

/// <summary>The odd sizes of <see cref="UnitySampleStabilityTests"/>.</summary>
public class UnitySampleStabilityOddSizeTests
{
    [Theory]
    [MemberData(nameof(UnitySampleStabilityTests.AllowedSizes), 1, MemberType = typeof(UnitySampleStabilityTests))]
    public void The_defaults_stay_stable_for_three_seconds(int particlesPerSide) =>
        UnitySampleStabilityTests.RunThreeSeconds(particlesPerSide);
}
