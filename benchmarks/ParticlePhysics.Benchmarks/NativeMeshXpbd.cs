using System;
using System.Runtime.InteropServices;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The plain C reference of the membrane and bending projections (<c>benchmarks/reference-c/mesh_xpbd.c</c>) called
/// in-process: it takes the elements as the library's forces copy them out, colours them as the library does, and
/// projects them with the library's expressions, so that a pass gives the library's positions to the last bit.
/// </summary>
internal sealed unsafe class NativeMeshXpbd : IDisposable
{
    public const string Library = "mesh_xpbd";
    private IntPtr _mesh;

    public NativeMeshXpbd(int particles, IMembraneElements membrane, IBendingElements bending)
    {
        NativeXpbd.EnsureLoaded();
        var corners = new int[3 * membrane.TriangleCount];
        var parameters = new double[8 * membrane.TriangleCount];
        membrane.CopyTriangles(corners, parameters);
        var slots = new int[6 * bending.ElementCount];
        var weights = new double[18 * bending.ElementCount];
        var stiffness = new double[bending.ElementCount];
        bending.CopyElements(slots, weights, stiffness);
        fixed (int* c = corners, s = slots)
        fixed (double* p = parameters, w = weights, k = stiffness)
        {
            _mesh = Create(particles, membrane.TriangleCount, c, p, bending.ElementCount, s, w, k);
        }
    }

    /// <summary>Readies the compliances for the substep <paramref name="h"/>.</summary>
    public void Prepare(double h) => Prepare(_mesh, h);

    /// <summary>
    /// <paramref name="passes"/> passes over <paramref name="x"/>: <paramref name="which"/> 1 the membrane, 2 the
    /// bending, 3 the membrane then the bending.
    /// </summary>
    public void Project(double[] x, double[] x0, double[] w, int passes, int which)
    {
        fixed (double* px = x, px0 = x0, pw = w)
        {
            Project(_mesh, px, px0, pw, passes, which);
        }
    }

    public void Dispose()
    {
        if (_mesh != IntPtr.Zero)
        {
            Destroy(_mesh);
            _mesh = IntPtr.Zero;
        }
    }

    [DllImport(Library, EntryPoint = "mesh_create")]
    private static extern IntPtr Create(int particles, int triangles, int* corners, double* parameters, int elements, int* slots, double* weights, double* stiffness);

    [DllImport(Library, EntryPoint = "mesh_prepare")]
    private static extern void Prepare(IntPtr mesh, double h);

    [DllImport(Library, EntryPoint = "mesh_project")]
    private static extern void Project(IntPtr mesh, double* x, double* x0, double* w, int passes, int which);

    [DllImport(Library, EntryPoint = "mesh_destroy")]
    private static extern void Destroy(IntPtr mesh);
}
