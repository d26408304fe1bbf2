using BenchmarkDotNet.Columns;
using BenchmarkDotNet.Configs;
using ParticlePhysics.Benchmarks.Columns;

namespace ParticlePhysics.Benchmarks;

/// <summary>The computed columns of the cloth-step benchmarks: time per particle and per spring evaluation.</summary>
public sealed class ClothColumnsConfig : ManualConfig
{
    public ClothColumnsConfig()
    {
        // Median and Min beside the Mean: on a shared machine the Min is the figure least disturbed by other work.
        AddColumn(StatisticColumn.Median, StatisticColumn.Min, PerWorkColumn.PerParticle, PerWorkColumn.PerSpringEvaluation);
    }
}

/// <summary>The computed columns of the integrator benchmarks: the time step used and the cost per simulated second.</summary>
public sealed class IntegratorColumnsConfig : ManualConfig
{
    public IntegratorColumnsConfig()
    {
        AddColumn(StatisticColumn.Median, StatisticColumn.Min, SimulatedTimeColumn.TimeStep, SimulatedTimeColumn.CostPerSimulatedSecond);
    }
}

/// <summary>The computed columns of the implicit Euler benchmarks: CG iterations per step and the cost per iteration.</summary>
public sealed class ImplicitColumnsConfig : ManualConfig
{
    public ImplicitColumnsConfig()
    {
        AddColumn(StatisticColumn.Median, StatisticColumn.Min, ImplicitIterationsColumn.IterationsPerStep, ImplicitIterationsColumn.MicrosecondsPerIteration);
    }
}

/// <summary>The computed column of the contact benchmarks: time per particle.</summary>
public sealed class ContactColumnsConfig : ManualConfig
{
    public ContactColumnsConfig()
    {
        AddColumn(StatisticColumn.Median, StatisticColumn.Min, PerParticleCountColumn.Instance);
    }
}

/// <summary>The computed columns of the xpbd benchmarks: ms per simulated second and ns per spring projection.</summary>
public sealed class XpbdColumnsConfig : ManualConfig
{
    public XpbdColumnsConfig()
    {
        AddColumn(StatisticColumn.Median, StatisticColumn.Min, XpbdWorkColumn.PerSimulatedSecond, XpbdWorkColumn.PerProjection);
    }
}
