using System;
using System.Collections.Generic;
using ParticlePhysics.Scenarios;

namespace ParticlePhysics.Demo.Running;

/// <summary>The course's scalar ODE dy/dt = -2 y t: rows <c>t,y,exact,error</c>, as the contract fixes them.</summary>
internal sealed class ScalarOdeSetup : ScenarioSetup
{
    private static readonly string[] _columns = { "t", "y", "exact", "error" };
    private static readonly string[] _summary = { "y" };
    private static readonly (string, string?)[] _plot = { ("y", "exact") };
    private readonly GaussianDecayOde _ode;

    public ScalarOdeSetup(GaussianDecayOde ode)
        : base("scalar-ode", ode)
    {
        _ode = ode;
    }

    public override IReadOnlyList<string> Columns => _columns;

    public override IReadOnlyList<string> TableColumns => _columns;

    public override IReadOnlyList<string> SummaryColumns => _summary;

    public override IReadOnlyList<(string Column, string? Exact)> PlotSeries => _plot;

    public override ISimulation CreateSimulation() =>
        new OdeSimulationAdapter(new OdeSimulation(_ode, new[] { GaussianDecayOde.InitialValue }));

    protected override void FillExact(double time, Span<double> row)
    {
        Span<double> exact = stackalloc double[1];
        _ode.ExactState(time, exact);
        row[2] = exact[0];
    }

    public override void FillRow(ISimulation simulation, double time, Span<double> row)
    {
        Span<double> exact = stackalloc double[1];
        _ode.ExactState(time, exact);
        var y = simulation.State[0];
        row[0] = time;
        row[1] = y;
        row[2] = exact[0];
        row[3] = Math.Abs(y - exact[0]);
    }
}
