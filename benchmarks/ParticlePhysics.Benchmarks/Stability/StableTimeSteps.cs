using System;
using System.Collections.Generic;
using System.Globalization;
using System.IO;
using System.Reflection;

namespace ParticlePhysics.Benchmarks.Stability;

/// <summary>
/// The largest stable time step of each integrator on the n x n cloth, as found by <see cref="StabilitySearch"/>
/// and saved by the stability mode in <c>stable-time-steps.csv</c> (embedded in this assembly), so that a benchmark
/// does not spend half a minute searching. An integrator missing from the file (a new one in the catalog) is
/// searched for on first use, with a note on the console to save it.
/// </summary>
internal static class StableTimeSteps
{
    public const string FileName = "stable-time-steps.csv";
    public const string Header = "integrator,n,dt";

    /// <summary>The output interval used for the adaptive rk45, which has no stability limit of its own.</summary>
    public const double AdaptiveOutputInterval = 0.001;

    private static readonly Dictionary<(string, int), double> _table = Load();

    /// <summary>True for integrators that choose their own internal steps (rk45).</summary>
    public static bool IsAdaptive(string integrator) => integrator == "rk45";

    /// <summary>The largest stable dt of <paramref name="integrator"/> on the n x n cloth.</summary>
    public static double For(string integrator, int particlesPerSide)
    {
        if (IsAdaptive(integrator))
        {
            return AdaptiveOutputInterval;
        }

        lock (_table)
        {
            if (!_table.TryGetValue((integrator, particlesPerSide), out var dt))
            {
                Console.WriteLine(
                    $"note: no stable dt saved for {integrator} at n = {particlesPerSide}; searching (run the stability mode with --write to save it).");
                dt = StabilitySearch.LargestStableTimeStep(integrator, particlesPerSide);
                _table[(integrator, particlesPerSide)] = dt;
            }

            return dt;
        }
    }

    /// <summary>
    /// The time step that lands exactly on whole simulated seconds: 1 / ceil(1 / dt), never above the stable dt.
    /// </summary>
    public static double Rounded(double dt) => 1.0 / Math.Ceiling(1.0 / dt);

    public static string Format(string integrator, int particlesPerSide, double dt) =>
        string.Create(CultureInfo.InvariantCulture, $"{integrator},{particlesPerSide},{dt:R}");

    private static Dictionary<(string, int), double> Load()
    {
        var table = new Dictionary<(string, int), double>();
        using var stream = Assembly.GetExecutingAssembly().GetManifestResourceStream(FileName);
        if (stream is null)
        {
            return table;
        }

        using var reader = new StreamReader(stream);
        while (reader.ReadLine() is { } line)
        {
            var fields = line.Split(',');
            if (line.Length == 0 || line.StartsWith('#') || line == Header || fields.Length != 3)
            {
                continue;
            }

            table[(fields[0], int.Parse(fields[1], CultureInfo.InvariantCulture))] =
                double.Parse(fields[2], CultureInfo.InvariantCulture);
        }

        return table;
    }
}
