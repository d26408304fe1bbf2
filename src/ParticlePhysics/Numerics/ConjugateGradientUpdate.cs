using System.Numerics;
using System.Runtime.CompilerServices;

namespace ParticlePhysics.Numerics;

/// <summary>
/// The update of one iteration of conjugate gradients in Chronopoulos and Gear's form (implicit Euler's solve), on
/// one component or a range of them: p = z + beta p, s = w + beta s with w = m z - jw (A z for A = M - J, from the
/// product jw = J z, which is then cleared for the next product), dv += alpha p, r -= alpha s.
/// </summary>
/// <remarks>
/// A kernel without state, so that the solver's own update pass and the multigrid's pass that fuses the update with
/// its restriction run the same operations in the same order.
/// </remarks>
internal static unsafe class ConjugateGradientUpdate
{
    /// <summary>The update of component k, with the mass of its particle; returns the new r_k.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static double Component(
        double* z, double* jw, double mass, double* p, double* s, double* dv, double* r, double alpha, double beta, long k)
    {
        var zk = z[k];
        var wk = (mass * zk) - jw[k];
        jw[k] = 0.0;
        var pk = zk + (beta * p[k]);
        p[k] = pk;
        var sk = wk + (beta * s[k]);
        s[k] = sk;
        dv[k] += alpha * pk;
        var rk = r[k] - (alpha * sk);
        r[k] = rk;
        return rk;
    }

    /// <summary>
    /// <see cref="Component"/> on components [<paramref name="begin"/>, <paramref name="end"/>), with the mass of
    /// each component's particle in <paramref name="masses"/> (3 values per particle): several components at a time with
    /// System.Numerics.Vector where the runtime accelerates it, one at a time otherwise. Each component gets the same
    /// multiplications, additions and subtractions in both, so the same bits.
    /// </summary>
    public static void Range(
        double* z, double* jw, double* masses, double* p, double* s, double* dv, double* r, double alpha, double beta, long begin, long end)
    {
        var k = begin;
        if (Vector.IsHardwareAccelerated)
        {
            var width = Vector<double>.Count;
            var alphas = new Vector<double>(alpha);
            var betas = new Vector<double>(beta);
            for (; k + width <= end; k += width)
            {
                // Whole vectors inside [begin, end) only, which the caller keeps inside the arrays.
                var zk = Load(z + k);
                var wk = (Load(masses + k) * zk) - Load(jw + k);
                Store(jw + k, Vector<double>.Zero);
                var pk = zk + (betas * Load(p + k));
                Store(p + k, pk);
                var sk = wk + (betas * Load(s + k));
                Store(s + k, sk);
                Store(dv + k, Load(dv + k) + (alphas * pk));
                Store(r + k, Load(r + k) - (alphas * sk));
            }
        }

        for (; k < end; k++)
        {
            _ = Component(z, jw, masses[k], p, s, dv, r, alpha, beta, k);
        }
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static Vector<double> Load(double* at) => *(Vector<double>*)at;

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static void Store(double* at, Vector<double> value) => *(Vector<double>*)at = value;
}
