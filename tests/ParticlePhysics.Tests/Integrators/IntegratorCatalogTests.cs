using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Tests.Integrators;

/// <summary>The catalog's names, and which integrator applies to which system.</summary>
public class IntegratorCatalogTests
{
    [Fact]
    public void Every_name_creates_an_integrator_that_answers_to_it()
    {
        Assert.Equal(
            new[] { "explicit-euler", "semi-implicit-euler", "implicit-euler", "rk4", "velocity-verlet", "rk45", "xpbd" },
            IntegratorCatalog.Names);
        foreach (var name in IntegratorCatalog.Names)
        {
            Assert.Equal(name, IntegratorCatalog.Create(name).Name);
        }
    }

    [Fact]
    public void Position_velocity_integrators_apply_to_particle_systems_only()
    {
        var cloth = new ClothScenario().Build();
        var scalar = new GaussianDecayOde();
        foreach (var name in IntegratorCatalog.Names)
        {
            Assert.True(IntegratorCatalog.AppliesTo(name, cloth));
            Assert.Equal(!IntegratorCatalog.NeedsSecondOrderSystem(name), IntegratorCatalog.AppliesTo(name, scalar));
        }

        Assert.False(IntegratorCatalog.AppliesTo("rk5", cloth));
        Assert.True(IntegratorCatalog.IsAdaptive("rk45"));
        Assert.False(IntegratorCatalog.IsAdaptive("rk4"));
        Assert.Equal(20, ((DormandPrince45)IntegratorCatalog.Create("rk45", 1e-6)).Tolerance * 2e7, 9);
    }

    [Fact]
    public void A_divergence_reports_the_limit_it_passed()
    {
        var system = new ClothScenario().Build();
        system.DivergenceLimit = 10;
        var ex = Assert.Throws<SimulationDivergedException>(() => Support.StateMetrics.Run(system, new RungeKutta4(), 1.0 / 60, 60));
        Assert.Equal(10, ex.Limit);
        Assert.True(System.Math.Abs(ex.Value) > 10);
    }
}
