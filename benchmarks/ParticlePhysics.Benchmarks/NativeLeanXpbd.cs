using System;
using System.Runtime.InteropServices;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The lean plain C xpbd of the course's cloth (<c>benchmarks/reference-c/cloth_xpbd_lean.c</c>: no damping, twelve
/// structured colour batches, separate arrays) called in-process, for the xpbd mode's <c>--lean</c> comparison. Its
/// projection order is not the library's, so its state is another sweep's: the comparison is of cost only.
/// </summary>
internal sealed class NativeLeanXpbd : IDisposable
{
    public const string Library = "cloth_xpbd_lean";
    private IntPtr _cloth;

    public NativeLeanXpbd(int particlesPerSide)
    {
        NativeXpbd.EnsureLoaded();
        _cloth = Create(particlesPerSide);
        if (_cloth == IntPtr.Zero)
        {
            throw new ArgumentOutOfRangeException(nameof(particlesPerSide), particlesPerSide, "n must be 3 to 2048.");
        }
    }

    /// <summary>The number of springs (the library's count, ClothScenario.SpringCount).</summary>
    public int SpringCount => Springs(_cloth);

    public void Reset() => Reset(_cloth);

    /// <summary><paramref name="steps"/> frames of <paramref name="dt"/>, <paramref name="substeps"/> substeps each.</summary>
    public void Run(double dt, int substeps, int steps) => Step(_cloth, dt, substeps, steps);

    /// <summary>The sum of the state [x | v].</summary>
    public double Checksum() => ChecksumOf(_cloth);

    public void Dispose()
    {
        if (_cloth != IntPtr.Zero)
        {
            Destroy(_cloth);
            _cloth = IntPtr.Zero;
        }
    }

    [DllImport(Library, EntryPoint = "lean_create")]
    private static extern IntPtr Create(int n);

    [DllImport(Library, EntryPoint = "lean_reset")]
    private static extern void Reset(IntPtr cloth);

    [DllImport(Library, EntryPoint = "lean_step")]
    private static extern void Step(IntPtr cloth, double dt, int substeps, int steps);

    [DllImport(Library, EntryPoint = "lean_checksum")]
    private static extern double ChecksumOf(IntPtr cloth);

    [DllImport(Library, EntryPoint = "lean_springs")]
    private static extern int Springs(IntPtr cloth);

    [DllImport(Library, EntryPoint = "lean_destroy")]
    private static extern void Destroy(IntPtr cloth);
}
