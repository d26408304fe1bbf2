using System;
using System.Diagnostics;
using System.IO;
using System.Runtime.InteropServices;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The plain C xpbd reference (<c>benchmarks/reference-c/cloth_xpbd.c</c>, gcc -O3) called in-process, so that
/// BenchmarkDotNet times it exactly as it times the library: <c>build/libcloth_xpbd.so</c>, built by
/// <c>reference-c/run.sh --build</c> (which this class runs when the library is missing or older than its source).
/// </summary>
internal sealed class NativeXpbd : IDisposable
{
    private const string Library = "cloth_xpbd";
    private static readonly object _gate = new();
    private static bool _resolverSet;
    private IntPtr _cloth;

    public NativeXpbd(int particlesPerSide)
    {
        EnsureLoaded();
        _cloth = Create(particlesPerSide);
        if (_cloth == IntPtr.Zero)
        {
            throw new ArgumentOutOfRangeException(nameof(particlesPerSide), particlesPerSide, "n must be 3 to 2048.");
        }
    }

    /// <summary>The number of springs of the C cloth (the library's count, ClothScenario.SpringCount).</summary>
    public int SpringCount => Springs(_cloth);

    /// <summary>The number of colours of the C colouring (the library's, ConstraintColouring).</summary>
    public int ColourCount => Colours(_cloth);

    /// <summary>The C reference's directory, benchmarks/reference-c.</summary>
    public static string SourceDirectory => Path.Combine(Program.RepositoryRoot(AppContext.BaseDirectory), "benchmarks", "reference-c");

    /// <summary>Back to the flat cloth at rest.</summary>
    public void Reset() => Reset(_cloth);

    /// <summary><paramref name="steps"/> frames of <paramref name="dt"/>, <paramref name="substeps"/> substeps each.</summary>
    public void Run(double dt, int substeps, int steps) => Step(_cloth, dt, substeps, steps);

    /// <summary>The sum of the state [x | v], as the library's <see cref="XpbdCloth.Checksum"/>.</summary>
    public double Checksum() => ChecksumOf(_cloth);

    /// <summary>The state [x | v], 6 n^2 values, laid out as the library's.</summary>
    public unsafe double[] State(int particles)
    {
        var state = new double[6 * particles];
        fixed (double* p = state)
        {
            CopyState(_cloth, p);
        }

        return state;
    }

    public void Dispose()
    {
        if (_cloth != IntPtr.Zero)
        {
            Destroy(_cloth);
            _cloth = IntPtr.Zero;
        }
    }

    /// <summary>
    /// Builds the shared libraries of benchmarks/reference-c if needed (gcc, through run.sh --build) and points the
    /// P/Invokes at them: this class's, <see cref="NativeLeanXpbd"/>'s and <see cref="NativeMeshXpbd"/>'s (an assembly
    /// has one resolver).
    /// </summary>
    internal static void EnsureLoaded()
    {
        lock (_gate)
        {
            if (_resolverSet)
            {
                return;
            }

            var directory = SourceDirectory;
            var libraries = new (string Name, string Source)[]
            {
                (Library, "cloth_xpbd.c"), (NativeLeanXpbd.Library, "cloth_xpbd_lean.c"), (NativeMeshXpbd.Library, "mesh_xpbd.c"),
                (NativeShapeMatching.Library, "shape_matching.c"),
            };
            string PathOf(string name) => Path.Combine(directory, "build", $"lib{name}.so");
            var stale = false;
            foreach (var (name, source) in libraries)
            {
                var library = PathOf(name);
                stale |= !File.Exists(library) || File.GetLastWriteTimeUtc(library) < File.GetLastWriteTimeUtc(Path.Combine(directory, source));
            }

            if (stale)
            {
                using var build = Process.Start(new ProcessStartInfo("bash", $"\"{Path.Combine(directory, "run.sh")}\" --build")
                {
                    RedirectStandardError = true,
                    UseShellExecute = false,
                }) ?? throw new InvalidOperationException("could not start bash to build the C reference");
                var errors = build.StandardError.ReadToEnd();
                build.WaitForExit();
                if (build.ExitCode != 0 || Array.Exists(libraries, l => !File.Exists(PathOf(l.Name))))
                {
                    throw new InvalidOperationException(
                        $"benchmarks/reference-c/run.sh --build failed (exit {build.ExitCode}); it needs gcc. {errors}");
                }
            }

            NativeLibrary.SetDllImportResolver(
                typeof(NativeXpbd).Assembly,
                (name, assembly, path) => Array.Exists(libraries, l => l.Name == name) ? NativeLibrary.Load(PathOf(name)) : IntPtr.Zero);
            _resolverSet = true;
        }
    }

    [DllImport(Library, EntryPoint = "xpbd_create")]
    private static extern IntPtr Create(int n);

    [DllImport(Library, EntryPoint = "xpbd_reset")]
    private static extern void Reset(IntPtr cloth);

    [DllImport(Library, EntryPoint = "xpbd_step")]
    private static extern void Step(IntPtr cloth, double dt, int substeps, int steps);

    [DllImport(Library, EntryPoint = "xpbd_checksum")]
    private static extern double ChecksumOf(IntPtr cloth);

    [DllImport(Library, EntryPoint = "xpbd_state")]
    private static extern unsafe void CopyState(IntPtr cloth, double* state);

    [DllImport(Library, EntryPoint = "xpbd_springs")]
    private static extern int Springs(IntPtr cloth);

    [DllImport(Library, EntryPoint = "xpbd_colours")]
    private static extern int Colours(IntPtr cloth);

    [DllImport(Library, EntryPoint = "xpbd_destroy")]
    private static extern void Destroy(IntPtr cloth);
}
