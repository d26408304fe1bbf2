using System;
using System.Globalization;
using System.IO;

namespace ParticlePhysics.Tests.Demo;

/// <summary>A bad command line: exit code 2, nothing on stdout, one line on stderr starting with "error:" that names the value.</summary>
public class DemoBadInputTests
{
    [Theory]
    [InlineData("unknown scenario", "fre-fall", "free-fall")]
    [InlineData("unknown option", "free-fall --dtt 0.1", "--dtt", "--dt")]
    [InlineData("unknown integrator", "free-fall --integrator rk5", "rk5", "rk4", "explicit-euler")]
    [InlineData("unknown format", "cloth --format xml", "xml", "table, csv, json")]
    [InlineData("zero dt", "free-fall --dt 0", "--dt", "'0'", "positive")]
    [InlineData("negative dt", "mass-spring-damper --dt -0.01", "--dt", "-0.01")]
    [InlineData("NaN dt", "free-fall --dt NaN", "--dt", "NaN")]
    [InlineData("text for a number", "free-fall --duration ten", "--duration", "ten")]
    [InlineData("fraction over zero", "cloth --resolution 1/0", "--resolution", "'1/0'", "fraction")]
    [InlineData("half a fraction", "free-fall --dt 1/", "--dt", "'1/'")]
    [InlineData("negative fraction", "free-fall --dt -1/100", "--dt", "'-1/100'", "positive")]
    [InlineData("infinite duration", "scalar-ode --duration Infinity", "--duration", "Infinity")]
    [InlineData("zero mass", "free-fall --mass 0", "--mass", "'0'")]
    [InlineData("negative mass", "two-mass-chain --m2 -1", "--m2", "-1")]
    [InlineData("zero size", "cloth --size 0", "--size", "'0'")]
    [InlineData("negative stiffness", "mass-spring-damper --stiffness -1", "--stiffness", "-1", ">= 0")]
    [InlineData("negative damping", "cloth --damping -0.5", "--damping", "-0.5")]
    [InlineData("negative drag", "free-fall --drag -0.01", "--drag", "-0.01")]
    [InlineData("resolution that does not divide the size", "cloth --resolution 0.3", "--resolution", "0.3", "--size")]
    [InlineData("integrator that needs positions and velocities", "scalar-ode --integrator semi-implicit-euler", "semi-implicit-euler", "scalar-ode", "rk4")]
    [InlineData("velocity verlet on the scalar ode", "scalar-ode --integrator velocity-verlet", "velocity-verlet", "explicit-euler")]
    [InlineData("convergence of a scenario without exact solution", "convergence cloth", "cloth", "free-fall")]
    [InlineData("convergence without a scenario", "convergence", "convergence", "scalar-ode")]
    [InlineData("bad every", "free-fall --every 0", "--every", "'0'")]
    [InlineData("bad levels", "convergence free-fall --levels 1", "--levels", "'1'", "2 to 16")]
    [InlineData("too many levels", "convergence free-fall --levels 17", "--levels", "'17'")]
    [InlineData("bad pin", "cloth --pin corner", "corner", "corners, edge, none")]
    [InlineData("option without its value", "free-fall --dt", "--dt")]
    [InlineData("stray argument", "free-fall 0.01", "0.01")]
    [InlineData("plot into a missing folder", "free-fall --plot /no/such/folder/x.svg", "/no/such/folder/x.svg")]
    [InlineData("angle of 0", "pendulum --angle 0", "--angle", "0", "between 0 and 180")]
    [InlineData("angle of 180", "pendulum --angle 180", "--angle", "180")]
    [InlineData("negative angle", "pendulum --angle -30", "--angle", "-30")]
    [InlineData("zero rod length", "pendulum --length 0", "--length", "'0'")]
    [InlineData("even particles", "hanging-chain --particles 10", "--particles", "'10'", "odd", "3 to 1001")]
    [InlineData("too few particles", "hanging-chain --particles 1", "--particles", "'1'", "3 to 1001")]
    [InlineData("too many particles", "hanging-chain --particles 1003", "--particles", "'1003'")]
    [InlineData("span as long as the chain", "hanging-chain --span 2", "--span", "2", "shorter", "--length")]
    [InlineData("span longer than the chain", "hanging-chain --length 1 --span 1.5", "--span", "1.5")]
    [InlineData("zero substeps", "cloth --integrator xpbd --substeps 0", "--substeps", "'0'", "1 to 1000")]
    [InlineData("too many substeps", "pendulum --integrator xpbd --substeps 1001", "--substeps", "'1001'")]
    [InlineData("fractional substeps", "hanging-chain --substeps 2.5", "--substeps", "'2.5'", "whole number")]
    [InlineData("substeps for the scalar ode", "scalar-ode --substeps 4", "--substeps", "scalar-ode")]
    [InlineData("xpbd on the scalar ode", "scalar-ode --integrator xpbd", "xpbd", "scalar-ode")]
    [InlineData("convergence of the chain", "convergence hanging-chain", "hanging-chain", "pendulum")]
    [InlineData("convergence of a pendulum with drag", "convergence pendulum --drag 0.1", "pendulum", "--drag 0")]

    // Issue 10. Item 12: a path that cannot be written is found before the run, not after it has printed.
    [InlineData("plot to a folder", "free-fall --plot /tmp", "--plot", "'/tmp'", "folder")]
    [InlineData("plot to the root", "cloth --plot /", "--plot", "'/'", "folder")]
    [InlineData("plot into a folder that refuses new files", "mass-spring-damper --plot /proc/x.svg", "--plot", "/proc/x.svg")]
    [InlineData("convergence plot to a folder", "convergence free-fall --plot /tmp", "--plot", "'/tmp'", "folder")]

    // Items 7 and 13: a mass whose inverse overflows.
    [InlineData("cloth mass whose inverse overflows", "cloth --mass 1e-320", "--mass", "'1e-320'", "1/m")]
    [InlineData("free-fall mass of the smallest double", "free-fall --mass 5e-324", "--mass", "'5e-324'")]
    [InlineData("chain mass just below the smallest", "two-mass-chain --m1 4.9e-309", "--m1", "'4.9e-309'")]
    [InlineData("cloth mass too small once split", "cloth --mass 1e-303 --resolution 1/1023", "--mass", "1048576 particles", "1/m")]

    // Item 2: a tolerance below 100 machine epsilons (rk45 would never finish).
    [InlineData("tolerance below machine precision", "free-fall --integrator rk45 --tolerance 1e-300", "--tolerance", "'1e-300'", "2.220446049250313E-14")]
    [InlineData("convergence tolerance below machine precision", "convergence free-fall --integrator rk45 --tolerance 1e-16", "--tolerance", "'1e-16'")]

    // Items 9, 10 and 15: runs the core cannot hold.
    [InlineData("more steps than a run can count", "free-fall --dt 1e-300 --duration 1", "--duration", "--dt", "steps")]
    [InlineData("a cloth beyond the world's limit", "cloth --resolution 1/2048", "--resolution", "2049", "2048")]
    // The contact scenarios' options (bouncing-ball, collision, drape) and the masses of every scenario.
    [InlineData("restitution above 1", "bouncing-ball --restitution 1.5", "--restitution", "'1.5'", "0 to 1")]
    [InlineData("negative restitution", "collision --restitution -0.1", "--restitution", "'-0.1'", "0 to 1")]
    [InlineData("NaN restitution", "bouncing-ball --restitution NaN", "--restitution", "NaN")]
    [InlineData("negative ground friction", "bouncing-ball --friction -1", "--friction", "'-1'", ">= 0")]
    [InlineData("infinite sphere friction", "drape --friction Infinity", "--friction", "Infinity")]
    [InlineData("negative ball radius", "bouncing-ball --radius -0.1", "--radius", "'-0.1'", ">= 0")]
    [InlineData("ball starting inside the ground", "bouncing-ball --radius 2 --height 1", "--height", "--radius", "inside the ground")]
    [InlineData("ball below the ground", "bouncing-ball --height -1", "--height", "-1", "inside the ground")]
    [InlineData("infinite height", "bouncing-ball --height Infinity", "--height", "Infinity")]
    [InlineData("text for a starting velocity", "bouncing-ball --vx0 fast", "--vx0", "'fast'")]
    [InlineData("ball mass whose inverse overflows", "bouncing-ball --mass 1e-320", "--mass", "'1e-320'", "1/m")]
    [InlineData("collision mass of 0", "collision --m1 0", "--m1", "'0'")]
    [InlineData("collision mass whose inverse overflows", "collision --m2 1e-320", "--m2", "'1e-320'", "1/m")]
    [InlineData("particles that start overlapping", "collision --radius 1", "--radius", "1", "overlap")]
    [InlineData("negative collision radius", "collision --radius -1", "--radius", "'-1'")]
    [InlineData("NaN starting velocity", "collision --v2 NaN", "--v2", "NaN")]
    [InlineData("sphere of radius 0", "drape --sphere-radius 0", "--sphere-radius", "'0'", "positive")]
    [InlineData("sphere through the cloth", "drape --sphere-y 0", "--sphere-y", "0", "inside", "0.31")]
    [InlineData("sphere touching the cloth from above", "drape --sphere-y 0.2", "--sphere-y", "0.2", "inside")]
    [InlineData("infinite sphere height", "drape --sphere-y Infinity", "--sphere-y", "Infinity")]
    [InlineData("negative particle radius", "drape --radius -0.01", "--radius", "'-0.01'")]
    [InlineData("drape resolution that does not divide the size", "drape --resolution 0.3", "--resolution", "0.3", "--size")]
    [InlineData("drape pin that does not exist", "drape --pin corner", "corner", "corners, edge, none")]
    [InlineData("drape mass whose inverse overflows", "drape --mass 1e-320", "--mass", "'1e-320'", "1/m")]
    [InlineData("drape mass too small once split", "drape --mass 1e-307", "--mass", "121 particles", "1/m")]
    [InlineData("pendulum mass whose inverse overflows", "pendulum --mass 1e-320", "--mass", "'1e-320'", "1/m")]
    [InlineData("chain mass whose inverse overflows", "hanging-chain --mass 1e-320", "--mass", "'1e-320'", "1/m")]
    [InlineData("substeps for the bouncing ball", "bouncing-ball --integrator xpbd --substeps 0", "--substeps", "'0'", "1 to 1000")]
    [InlineData("xpbd substeps for the drape", "drape --integrator xpbd --substeps 1001", "--substeps", "'1001'")]
    [InlineData("convergence of the drape", "convergence drape", "drape", "free-fall")]
    [InlineData("replay page to a folder", "cloth --animate /tmp", "--animate", "'/tmp'", "folder")]
    [InlineData("replay page into a folder that refuses new files", "bouncing-ball --animate /proc/x.html", "--animate", "/proc/x.html")]
    public void Is_refused_with_one_error_line_and_exit_code_2(string what, string commandLine, params string[] mentioned)
    {
        var result = DemoProcess.Run(commandLine.Split(' '));

        Assert.True(result.ExitCode == 2, $"{what}: exit code {result.ExitCode}, stderr: {result.Error}");
        Assert.Equal("", result.Output);
        var line = Assert.Single(result.ErrorLines);
        Assert.StartsWith("error: ", line, StringComparison.Ordinal);
        foreach (var text in mentioned)
        {
            Assert.Contains(text, line, StringComparison.Ordinal);
        }

        Assert.DoesNotContain("   at ", result.Error, StringComparison.Ordinal); // no stack trace
    }

    [Fact]
    public void A_read_only_plot_file_is_refused_before_the_run_and_left_as_it_was()
    {
        // Item 12: before, the run printed all its rows, then failed to write the plot (or, as root, overwrote it).
        var path = Path.Combine(Path.GetTempPath(), $"robust-read-only-{Guid.NewGuid():N}.svg");
        File.WriteAllText(path, "keep me");
        File.SetAttributes(path, FileAttributes.ReadOnly);
        try
        {
            var result = DemoProcess.Run("cloth", "--plot", path);

            Assert.Equal(2, result.ExitCode);
            Assert.Equal("", result.Output);
            var line = Assert.Single(result.ErrorLines);
            Assert.Contains(path, line, StringComparison.Ordinal);
            Assert.Contains("read-only", line, StringComparison.Ordinal);
            Assert.Equal("keep me", File.ReadAllText(path));
        }
        finally
        {
            File.SetAttributes(path, FileAttributes.Normal);
            File.Delete(path);
        }
    }

    [Fact]
    public void Checking_a_plot_path_that_does_not_exist_yet_leaves_no_file_behind_when_the_run_is_refused()
    {
        var path = Path.Combine(Path.GetTempPath(), $"robust-probe-{Guid.NewGuid():N}.svg");
        var result = DemoProcess.Run("cloth", "--plot", path, "--mass", "0");

        Assert.Equal(2, result.ExitCode);
        Assert.False(File.Exists(path));
    }

    [Theory]
    [InlineData("fr-FR")]
    [InlineData("de-DE")]
    public void Under_a_french_or_german_locale_every_message_is_english(string culture)
    {
        // Item 14: System.CommandLine's "missing value" came in the machine's language, every other message in English.
        var missing = DemoProcess.RunUnder(new CultureInfo(culture), "free-fall", "--dt");
        Assert.Equal(2, missing.ExitCode);
        Assert.Equal("error: --dt needs a value; run 'free-fall --help' to see what it takes.", Assert.Single(missing.ErrorLines));

        var english = DemoProcess.Run("cloth", "--format");
        var localised = DemoProcess.RunUnder(new CultureInfo(culture), "cloth", "--format");
        Assert.Equal(english.Error, localised.Error);

        var help = DemoProcess.RunUnder(new CultureInfo(culture), "free-fall", "--help");
        Assert.Equal(DemoProcess.Run("free-fall", "--help").Output, help.Output);
    }

    [Fact]
    public void A_fraction_is_a_number_so_1_over_127_gives_the_128_by_128_cloth()
    {
        var result = DemoProcess.Run("cloth", "--resolution", "1/127", "--dt", "0.0001", "--duration", "0.0002", "--format", "csv");

        Assert.True(result.ExitCode == 0, result.Error);
        var header = result.Output.Split('\n')[0].Split(',');
        Assert.Contains("vz16383", header);
        Assert.DoesNotContain("x16384", header);
    }

    [Fact]
    public void A_misspelled_option_gets_a_suggestion()
    {
        var result = DemoProcess.Run("mass-spring-damper", "--stifness", "3");

        Assert.Equal(2, result.ExitCode);
        Assert.Contains("did you mean '--stiffness'?", result.Error, StringComparison.Ordinal);
    }

    [Fact]
    public void Negative_numbers_are_values_where_they_are_allowed()
    {
        var result = DemoProcess.Run("mass-spring-damper", "--y0", "-2", "--v0", "-1.5", "--format", "csv", "--duration", "0.01");

        Assert.Equal(0, result.ExitCode);
        var (_, rows) = result.Csv();
        Assert.Equal(-2.0, rows[0][2]);
        Assert.Equal(-1.5, rows[0][5]);
    }
}
