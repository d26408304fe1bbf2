using System;
using System.Diagnostics;
using System.Globalization;
using System.IO;
using System.Linq;
using System.Text;
using ParticlePhysics.Scenes.Meshes;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// <c>obj [--vertices 1000000] [--rounds 7]</c>: the OBJ reader's throughput on a generated mesh, outside
/// BenchmarkDotNet (one read is a large fraction of a second): a square grid of about that many vertices written as
/// <c>v x y z</c> lines with six decimals and quads as <c>f a/a/a b/b/b c/c/c d/d/d</c> (the v/vt/vn form exporters
/// write), in a temporary folder; each round reads it whole from the file, and the fastest and median rounds are
/// printed in MB/s (the target: at least 50 MB/s).
/// </summary>
internal static class ObjThroughput
{
    public static int Run(string[] args)
    {
        var vertices = Option(args, "--vertices", 1_000_000);
        var rounds = Option(args, "--rounds", 7);
        var side = (int)Math.Ceiling(Math.Sqrt(vertices));
        var folder = Directory.CreateTempSubdirectory("obj-throughput-");
        try
        {
            var path = Path.Combine(folder.FullName, "grid.obj");
            Write(path, side);
            var bytes = new FileInfo(path).Length;
            var seconds = new double[rounds];
            TriangleMesh? mesh = null;
            for (var r = 0; r < rounds; r++)
            {
                var clock = Stopwatch.StartNew();
                mesh = ObjReader.Read(path);
                seconds[r] = clock.Elapsed.TotalSeconds;
            }

            Array.Sort(seconds);
            var mb = bytes / 1e6;
            Console.WriteLine(string.Format(
                CultureInfo.InvariantCulture,
                "obj: {0:N0} vertices, {1:N0} triangles, {2:F1} MB; fastest of {3} reads {4:F3} s ({5:F0} MB/s), median {6:F3} s ({7:F0} MB/s)",
                mesh!.VertexCount,
                mesh.TriangleCount,
                mb,
                rounds,
                seconds[0],
                mb / seconds[0],
                seconds[rounds / 2],
                mb / seconds[rounds / 2]));
            return 0;
        }
        finally
        {
            folder.Delete(recursive: true);
        }
    }

    private static void Write(string path, int side)
    {
        using var writer = new StreamWriter(path, false, new UTF8Encoding(false), 1 << 20);
        writer.WriteLine("# a grid for the OBJ throughput benchmark");
        writer.WriteLine("o grid");
        for (var row = 0; row < side; row++)
        {
            for (var col = 0; col < side; col++)
            {
                var x = col / (double)side;
                var z = row / (double)side;
                var y = 0.05 * Math.Sin(7 * x) * Math.Cos(5 * z);
                writer.Write("v ");
                writer.Write(x.ToString("F6", CultureInfo.InvariantCulture));
                writer.Write(' ');
                writer.Write(y.ToString("F6", CultureInfo.InvariantCulture));
                writer.Write(' ');
                writer.WriteLine(z.ToString("F6", CultureInfo.InvariantCulture));
            }
        }

        writer.WriteLine("s off");
        for (var row = 0; row + 1 < side; row++)
        {
            for (var col = 0; col + 1 < side; col++)
            {
                var a = (row * side) + col + 1;
                int b = a + 1, c = a + side + 1, d = a + side;
                writer.WriteLine(string.Format(CultureInfo.InvariantCulture, "f {0}/{0}/{0} {1}/{1}/{1} {2}/{2}/{2} {3}/{3}/{3}", a, b, c, d));
            }
        }
    }

    private static int Option(string[] args, string name, int defaultValue)
    {
        var at = Array.IndexOf(args, name);
        return at >= 0 && at + 1 < args.Length ? int.Parse(args[at + 1], CultureInfo.InvariantCulture) : defaultValue;
    }
}
