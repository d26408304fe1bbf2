using System;
using System.Runtime.InteropServices;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The plain C reference of the rigid bodies' shape matching (<c>benchmarks/reference-c/shape_matching.c</c>) called
/// in-process: the library's bodies (their particles and rest offsets), projected and given their velocity
/// field with the library's expressions (its own sin and cos included), so that a pass gives the library's bits.
/// </summary>
internal sealed unsafe class NativeShapeMatching : IDisposable
{
    public const string Library = "shape_matching";
    private IntPtr _set;

    /// <param name="bodies">How many bodies.</param>
    /// <param name="per">Entries per body: body b holds entries b per to b per + per - 1.</param>
    /// <param name="particles">Each entry's particle.</param>
    /// <param name="rest">Each entry's rest offset, three numbers.</param>
    public NativeShapeMatching(int bodies, int per, int[] particles, double[] rest)
    {
        NativeXpbd.EnsureLoaded();
        fixed (int* p = particles)
        fixed (double* r = rest)
        {
            _set = Create(bodies, per, p, r);
        }

        if (_set == IntPtr.Zero)
        {
            throw new ArgumentOutOfRangeException(nameof(bodies), bodies, "bodies and per must be at least 1.");
        }
    }

    /// <summary>Back to every body at rest orientation.</summary>
    public void Reset() => Reset(_set);

    /// <summary><paramref name="passes"/> substeps of the projection then the velocity pass, on the arrays given.</summary>
    public void Run(double h, double[] x0, double[] x, double[] v, double[] m, double[] w, int passes)
    {
        fixed (double* px0 = x0, px = x, pv = v, pm = m, pw = w)
        {
            Run(_set, h, px0, px, pv, pm, pw, passes);
        }
    }

    public void Dispose()
    {
        if (_set != IntPtr.Zero)
        {
            Destroy(_set);
            _set = IntPtr.Zero;
        }
    }

    [DllImport(Library, EntryPoint = "sm_create")]
    private static extern IntPtr Create(int bodies, int per, int* particles, double* rest);

    [DllImport(Library, EntryPoint = "sm_reset")]
    private static extern void Reset(IntPtr set);

    [DllImport(Library, EntryPoint = "sm_run")]
    private static extern void Run(IntPtr set, double h, double* x0, double* x, double* v, double* m, double* w, int passes);

    [DllImport(Library, EntryPoint = "sm_destroy")]
    private static extern void Destroy(IntPtr set);
}
