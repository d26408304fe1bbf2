using System;
using System.Collections.Generic;
using System.Linq;
using System.Reflection;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Unity;

/// <summary>
/// The sample's Inspector defaults stay stable at every size its slider allows: 3 simulated seconds at 60 Hz from
/// rest, the solver converging at every step, no divergence, every particle near a pin.
/// </summary>
public class UnitySampleStabilityTests
{
    private const int Frames = 180;

    /// <summary>Every value of the sample's particlesPerSide slider ([Range] on the field).</summary>
    public static IEnumerable<object[]> AllowedSizes()
    {
        using var player = new UnityPlayer();
        var range = player.SampleType.GetField("particlesPerSide")!.GetCustomAttributes()
            .Single(a => a.GetType().FullName == "UnityEngine.RangeAttribute");
        var min = (int)(float)range.GetType().GetField("min")!.GetValue(range)!;
        var max = (int)(float)range.GetType().GetField("max")!.GetValue(range)!;
        Assert.Equal((2, 64), (min, max));
        return Enumerable.Range(min, max - min + 1).Select(n => new object[] { n });
    }

    [Theory]
    [MemberData(nameof(AllowedSizes))]
    public void The_defaults_stay_stable_for_three_seconds(int particlesPerSide)
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
}
