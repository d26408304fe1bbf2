using System;
using System.Globalization;
using System.IO;
using System.Runtime.CompilerServices;
using System.Text;
using ParticlePhysics.Demo;
using ParticlePhysics.Demo.Running;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenarios;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Demo;

/// <summary>
/// Issue 10, item 15: before a very long or very large run the demo says on stderr what it will cost (steps, time,
/// memory), before anything is printed on stdout and before the world is built. The tests stop the run at that line,
/// as a user would press Ctrl-C after reading it.
/// </summary>
[Collection(AllocationMeasurements.Name)]
public class DemoRunCostTests
{
    [Fact]
    public void Two_billion_steps_are_announced_with_their_cost_before_the_first_row()
    {
        var note = NoteOf("cloth", "--duration", "1e6", "--dt", "0.0005");

        Assert.StartsWith("note: cloth will take 2,000,000,000 steps of 0.0005 s with rk4 on 121 particles and 618 springs: about ", note, StringComparison.Ordinal);
        Assert.Matches(@"about \d+ (h|days) ", note);
        Assert.Contains("of memory", note, StringComparison.Ordinal);
    }

    [Fact]
    public void A_2048_by_2048_cloth_is_announced_with_its_gigabytes_before_they_are_allocated()
    {
        var before = GC.GetTotalMemory(forceFullCollection: true);
        var note = NoteOf("cloth", "--resolution", "1/2047", "--duration", "0.001");
        var held = GC.GetTotalMemory(forceFullCollection: true) - before;

        Assert.Contains("on 4,194,304 particles and 25,145,346 springs", note, StringComparison.Ordinal);
        Assert.Matches(@"and [3-4]\.\d GB of memory", note);
        Assert.True(held < 64 << 20, $"{held} bytes held when the note was printed");
    }

    [Fact]
    public void A_short_small_run_says_nothing_of_its_cost()
    {
        var result = DemoProcess.Run("cloth", "--duration", "0.01");
        Assert.Equal(0, result.ExitCode);
        Assert.Equal("", result.Error);
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("implicit-euler")]
    [InlineData("rk45")]
    [InlineData("explicit-euler")]
    public void The_memory_estimate_is_within_a_quarter_of_what_the_run_holds(string integrator)
    {
        // Measured: the bytes the garbage collector finds alive once the 64 x 64 cloth has been built, its column
        // names made, one row allocated and one step taken, against what RunCost adds up from the array sizes.
        // GC.GetTotalMemory is process-wide, so one measurement can be low when something else in the test process is
        // freed meanwhile: the median of three runs, each in a method of its own so that nothing of one run is still
        // alive when the next takes its "before".
        var plan = new RunPlan(integrator, 0.001, 1, 1, 1e-8);
        var held = new[] { HeldByOneRun(integrator, plan), HeldByOneRun(integrator, plan), HeldByOneRun(integrator, plan) };
        Array.Sort(held);

        var setup = new ClothSetup("cloth", new ClothScenario { Resolution = 1.0 / 63 }.Build, 64);
        var estimate = RunCost.For(setup, plan).Bytes;
        Assert.InRange(estimate, 0.75 * held[1], 1.25 * held[1]);
    }

    [MethodImpl(MethodImplOptions.NoInlining)]
    private static long HeldByOneRun(string integrator, RunPlan plan)
    {
        var before = GC.GetTotalMemory(forceFullCollection: true);
        var setup = new ClothSetup("cloth", new ClothScenario { Resolution = 1.0 / 63 }.Build, 64);
        var columns = setup.Columns;
        var simulation = setup.TakeSimulation();
        var method = IntegratorCatalog.Create(integrator);
        simulation.Step(method, plan.Dt);
        var row = new double[columns.Count];
        var held = GC.GetTotalMemory(forceFullCollection: true) - before;
        GC.KeepAlive(setup);
        GC.KeepAlive(simulation);
        GC.KeepAlive(method);
        GC.KeepAlive(row);
        return held;
    }

    /// <summary>Runs the demo until it writes its cost note on stderr, and returns that line; fails if a row comes first.</summary>
    private static string NoteOf(params string[] args)
    {
        var error = new StopAtNote();
        var output = new ThrowOnWrite();
        var stopped = Assert.Throws<NoteSeen>(() => Program.Run(args, output, error));
        return stopped.Message;
    }

    private sealed class NoteSeen : Exception
    {
        public NoteSeen(string message)
            : base(message)
        {
        }
    }

    /// <summary>stderr: throws with the line when the cost note arrives.</summary>
    private sealed class StopAtNote : StringWriter
    {
        public StopAtNote()
            : base(CultureInfo.InvariantCulture)
        {
        }

        public override void WriteLine(string? value)
        {
            if (value is not null && value.StartsWith("note:", StringComparison.Ordinal))
            {
                throw new NoteSeen(value);
            }

            base.WriteLine(value);
        }
    }

    /// <summary>stdout: the run must not start before the note.</summary>
    private sealed class ThrowOnWrite : StringWriter
    {
        public ThrowOnWrite()
            : base(CultureInfo.InvariantCulture)
        {
        }

        public override Encoding Encoding => Encoding.UTF8;

        public override void Write(char value) => throw new InvalidOperationException("stdout was written before any cost note");

        public override void Write(string? value) => throw new InvalidOperationException("stdout was written before any cost note: " + value);

        public override void WriteLine(string? value) => throw new InvalidOperationException("stdout was written before any cost note: " + value);
    }
}
