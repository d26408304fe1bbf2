using System;
using System.Collections.Generic;
using System.IO;
using System.Linq;
using System.Reflection;
using System.Runtime.Loader;

// The host of run.sh: loads the shim of each side (each with its own library) into its own load context, so that
// both run in this one process, then alternates them round by round (which goes first alternates too), so that both
// see the same machine from one second to the next. Prints each side's fastest and median round, the median and
// quartiles of the per-round ratios B / A, and whether both sides ended in the same bits.
//   Host dirA dirB rounds tolA tolB n integrator steps
var rounds = int.Parse(args[2]);
var tolerances = new[] { double.Parse(args[3], System.Globalization.CultureInfo.InvariantCulture), double.Parse(args[4], System.Globalization.CultureInfo.InvariantCulture) };
var n = int.Parse(args[5]);
var integrator = args[6];
var steps = int.Parse(args[7]);
var run = new Func<double>[2];
var iterations = new Func<long>[2];
var stateHash = new Func<ulong>[2];
for (var side = 0; side < 2; side++)
{
    var dir = Path.GetFullPath(args[side]);
    var shim = new SideContext(dir).LoadFromAssemblyPath(Path.Combine(dir, "Shim.dll")).GetType("Shim")!;
    var instance = Activator.CreateInstance(shim, n, tolerances[side], integrator, steps)!;
    var round = shim.GetMethod("Round")!;
    var count = shim.GetProperty("Iterations")!;
    run[side] = () => (double)round.Invoke(instance, null)!;
    iterations[side] = () => (long)count.GetValue(instance)!;
    var hash = shim.GetProperty("StateHash")!;
    stateHash[side] = () => (ulong)hash.GetValue(instance)!;
}

for (var warm = 0; warm < 3; warm++)
{
    run[0]();
    run[1]();
}

var times = new[] { new List<double>(), new List<double>() };
for (var r = 0; r < rounds; r++)
{
    var first = r % 2;
    times[first].Add(run[first]());
    times[1 - first].Add(run[1 - first]());
}

var ratios = times[0].Zip(times[1], (a, b) => b / a).OrderBy(x => x).ToList();
double Median(List<double> values) => values.OrderBy(x => x).ElementAt(values.Count / 2);
string Side(int s, string name) => FormattableString.Invariant(
    $"{name}{(integrator == "implicit-euler" ? $" (tolerance {tolerances[s]:R}, {iterations[s]() / 60.0:F2} CG it/frame)" : "")}: fastest {times[s].Min():F1} ms, median {Median(times[s]):F1} ms per simulated second");
Console.WriteLine(Side(0, "A"));
Console.WriteLine(Side(1, "B"));
Console.WriteLine(FormattableString.Invariant(
    $"B / A over {rounds} alternating rounds: median {ratios[ratios.Count / 2]:F3}, quartiles {ratios[ratios.Count / 4]:F3} to {ratios[3 * ratios.Count / 4]:F3}; fastest rounds {times[1].Min() / times[0].Min():F3}"));
Console.WriteLine(stateHash[0]() == stateHash[1]()
    ? "same bits: A and B end the second in the same state"
    : "other bits: A and B end the second in different states");

/// <summary>Resolves a side's library from its own folder, so that the two sides' libraries do not meet.</summary>
internal sealed class SideContext : AssemblyLoadContext
{
    private readonly string _dir;

    public SideContext(string dir)
        : base(dir)
    {
        _dir = dir;
    }

    protected override Assembly? Load(AssemblyName name)
    {
        var path = Path.Combine(_dir, name.Name + ".dll");
        return File.Exists(path) ? LoadFromAssemblyPath(path) : null;
    }
}
