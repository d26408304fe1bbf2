using System;
using ParticlePhysics.Aerodynamics;
using ParticlePhysics.Cloth;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Cloth;
using ParticlePhysics.Tests.Engine;
using ParticlePhysics.Tests.Support;
using Xunit.Abstractions;

namespace ParticlePhysics.Tests.Aerodynamics;

/// <summary>A flag pinned along its pole in a 5 m/s wind (issue 30): it streams out downwind and flutters.</summary>
public class FlagTests
{
    private readonly ITestOutputHelper _output;

    public FlagTests(ITestOutputHelper output) => _output = output;

    [Theory]
    [InlineData("xpbd")]
    [InlineData("implicit-euler")]
    public void A_flag_in_a_5_m_s_wind_streams_out_downwind_and_flutters(string integrator)
    {
        var (meanX, meanY, zRange, lastSecondPath) = Fly(new Air(1.2, new Vector3d(5, 0, 0), 1.2, 0.5), integrator);
        _output.WriteLine($"{integrator}: the tip's mean x {meanX:F3} m and y {meanY:F3} m (pole at x = 0, the flag 1.5 m long, the tip at y = 1.5 m at rest), "
            + $"z from 2 s to 6 s over {zRange:F3} m, {lastSecondPath:F3} m of z travelled in the last second");

        // Downwind: the tip at over 80 % of the flag's length from the pole and less than a third of it below where it started.
        Assert.True(meanX > 0.8 * 1.5, $"the tip's mean x is {meanX:F3} m");
        Assert.True(meanY > 1.5 - 0.5, $"the tip's mean y is {meanY:F3} m");

        // Flutters: across the wind, the tip sweeps over 10 cm, and is still moving in the last second.
        Assert.True(zRange > 0.1, $"the tip's z spans {zRange:F3} m");
        Assert.True(lastSecondPath > 0.1, $"the tip moved {lastSecondPath:F3} m across the wind in the last second");
    }

    [Fact]
    public void Without_wind_the_flag_hangs_from_its_pole()
    {
        var (meanX, meanY, _, _) = Fly(new Air(1.2, Vector3d.Zero, 1.2, 0.5), "xpbd");
        _output.WriteLine($"still air: the tip's mean x {meanX:F3} m, y {meanY:F3} m");
        Assert.True(meanX < 0.5, $"the tip's mean x is {meanX:F3} m");
    }

    [Theory]
    [MemberData(nameof(DeterminismAndAllocationTests.Integrators), MemberType = typeof(DeterminismAndAllocationTests))]
    public void A_flag_in_a_gusty_wind_steps_without_allocating_and_repeats_bit_for_bit(string integrator)
    {
        static TriangleCloth Gusty() => Flag(new Air(1.2, new Vector3d(5, 0, 0), 1.2, 0.5)
        {
            Gust = new Gust(new GustWave(new Vector3d(0, 0, 0.6), 0.7, new Vector3d(0.9, 0, 0)), new GustWave(new Vector3d(1, 0, 0), 0.3, new Vector3d(0.4, 0, 0), 1)),
        });
        // The membrane (2,000 N/m on particles of 0.4 g) holds the explicit integrators to small steps.
        var dt = integrator is "xpbd" or "implicit-euler" or "rk45" ? 1e-3 : 2e-5;
        var flag = Gusty();
        var stepper = IntegratorCatalog.Create(integrator);
        StateMetrics.Run(flag.System, stepper, dt, 3);
        var steps = 3;
        var allocated = ThreadAllocations.Measure(() =>
        {
            StateMetrics.Run(flag.System, stepper, dt, 10);
            steps += 10; // Measure runs the work again when the runtime's count is spurious
        });
        Assert.Equal(0, allocated);

        var again = Gusty();
        StateMetrics.Run(again.System, IntegratorCatalog.Create(integrator), dt, steps);
        Assert.Equal(StateMetrics.BitHash(flag.System.State), StateMetrics.BitHash(again.System.State));
    }

    [Fact]
    public void The_flag_in_wind_sample_scene_holds_its_golden_bits()
    {
        // The same hash is compared between Mono and CoreCLR by .ci/mono (tests/mono/RuntimeComparison.cs).
        var hash = SampleScenes.BitHashAfter("flag-in-wind.json", 120);
        _output.WriteLine(hash);
        Assert.Equal("7E4A78C8ADFD96502AB057FBB5329B3165541CF89CEBFA3A9F3857C201F62A37", hash);
    }

    private static (double MeanX, double MeanY, double ZRange, double LastSecondPath) Fly(Air air, string integrator)
    {
        const double dt = 1.0 / 60;
        var flag = Flag(air);
        var world = flag.System;
        var method = IntegratorCatalog.Create(integrator);
        var tip = TipParticle(flag);
        double zMin = double.MaxValue, zMax = double.MinValue, xSum = 0, ySum = 0, path = 0, z = 0;
        var count = 0;
        for (var s = 1; s <= 360; s++)
        {
            world.Step(method, dt);
            var p = world.GetPosition(tip);
            if (s > 120)
            {
                zMin = Math.Min(zMin, p.Z);
                zMax = Math.Max(zMax, p.Z);
                xSum += p.X;
                ySum += p.Y;
                count++;
            }

            if (s > 300)
            {
                path += Math.Abs(p.Z - z);
            }

            z = p.Z;
        }

        return (xSum / count, ySum / count, zMax - zMin, path);
    }

    internal static TriangleCloth Flag(Air air)
    {
        // 1.5 m along x by 1 m along y, 30 x 20 cells, in the plane z = 0 but for a ripple of 1 cm; pinned at x = 0.
        var (vertices, triangles) = ClothMeshes.Strip(30, 20, 0.05, 0.05);
        for (var v = 0; v < vertices.Length / 3; v++)
        {
            double x = vertices[3 * v], z = vertices[(3 * v) + 2];
            vertices[3 * v] = x;
            vertices[(3 * v) + 1] = 2.0 - z;
            vertices[(3 * v) + 2] = 0.01 * Math.Sin(4 * x);
        }

        var builder = new MeshClothBuilder(new WeldedMesh(vertices, triangles)) { Air = air, AreaDensity = 0.15, Modulus = 2000, Poisson = 0.3, MembraneDamping = 0.5, BendingRigidity = 1e-4 };
        for (var v = 0; v <= 20; v++)
        {
            builder.Pin(v);
        }

        return builder.Build();
    }

    internal static int TipParticle(TriangleCloth flag) => flag.ParticleIndex((30 * 21) + 10);
}
