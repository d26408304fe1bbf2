using System;
using System.Numerics;
using System.Runtime.InteropServices;

namespace ParticlePhysics.Numerics;

/// <summary>
/// The element-wise passes over whole state vectors (integrator stages, drag), with SIMD where the runtime
/// accelerates System.Numerics.Vector (CoreCLR) and plain loops where it does not (Unity's Mono and IL2CPP).
/// Each element gets the same multiply and add in both paths, so the results are bit-identical.
/// </summary>
internal static class VectorKernels
{
    /// <summary>first: next = y + a k and stage = y + b k; otherwise next += a k and stage = y + b k.</summary>
    public static void Stage(Span<double> next, Span<double> stage, ReadOnlySpan<double> y, ReadOnlySpan<double> k, double a, double b, bool first)
    {
        var n = y.Length;
        next = next.Slice(0, n);
        stage = stage.Slice(0, n);
        var yr = y.ForReading();
        var kr = k.Slice(0, n).ForReading();
        var i = 0;
        if (Vector.IsHardwareAccelerated)
        {
            var nv = MemoryMarshal.Cast<double, Vector<double>>(next);
            var sv = MemoryMarshal.Cast<double, Vector<double>>(stage);
            var yv = MemoryMarshal.Cast<double, Vector<double>>(yr);
            var kv = MemoryMarshal.Cast<double, Vector<double>>(kr);
            var av = new Vector<double>(a);
            var bv = new Vector<double>(b);
            for (var j = 0; j < yv.Length; j++)
            {
                nv[j] = (first ? yv[j] : nv[j]) + (av * kv[j]);
                sv[j] = yv[j] + (bv * kv[j]);
            }

            i = yv.Length * Vector<double>.Count;
        }

        for (; i < n; i++)
        {
            next[i] = (first ? yr[i] : next[i]) + (a * kr[i]);
            stage[i] = yr[i] + (b * kr[i]);
        }
    }

    /// <summary>target += a source.</summary>
    public static void AddScaled(Span<double> target, ReadOnlySpan<double> source, double a)
    {
        var n = source.Length;
        target = target.Slice(0, n);
        var s = source.ForReading();
        var i = 0;
        if (Vector.IsHardwareAccelerated)
        {
            var tv = MemoryMarshal.Cast<double, Vector<double>>(target);
            var sv = MemoryMarshal.Cast<double, Vector<double>>(s);
            var av = new Vector<double>(a);
            for (var j = 0; j < sv.Length; j++)
            {
                tv[j] += av * sv[j];
            }

            i = sv.Length * Vector<double>.Count;
        }

        for (; i < n; i++)
        {
            target[i] += a * s[i];
        }
    }

    /// <summary>
    /// The semi-implicit Euler prediction of a position-based substep: x0 = x, v0 = v, then v = v0 + h a and
    /// x = x0 + h v, element by element (all five spans of one length).
    /// </summary>
    public static void Predict(Span<double> x, Span<double> v, Span<double> x0, Span<double> v0, ReadOnlySpan<double> a, double h)
    {
        var n = a.Length;
        x = x.Slice(0, n);
        v = v.Slice(0, n);
        x0 = x0.Slice(0, n);
        v0 = v0.Slice(0, n);
        var ar = a.ForReading();
        var i = 0;
        if (Vector.IsHardwareAccelerated)
        {
            var xv = MemoryMarshal.Cast<double, Vector<double>>(x);
            var vv = MemoryMarshal.Cast<double, Vector<double>>(v);
            var x0v = MemoryMarshal.Cast<double, Vector<double>>(x0);
            var v0v = MemoryMarshal.Cast<double, Vector<double>>(v0);
            var av = MemoryMarshal.Cast<double, Vector<double>>(ar);
            var hv = new Vector<double>(h);
            for (var j = 0; j < av.Length; j++)
            {
                var xj = xv[j];
                var vj = vv[j];
                x0v[j] = xj;
                v0v[j] = vj;
                vj += hv * av[j];
                vv[j] = vj;
                xv[j] = xj + (hv * vj);
            }

            i = av.Length * Vector<double>.Count;
        }

        for (; i < n; i++)
        {
            var xi = x[i];
            var vi = v[i];
            x0[i] = xi;
            v0[i] = vi;
            vi += h * ar[i];
            v[i] = vi;
            x[i] = xi + (h * vi);
        }
    }

    /// <summary>target -= a source (drag: F -= lambda v); t + (-a) s is exactly t - a s, so this is AddScaled.</summary>
    public static void SubtractScaled(Span<double> target, ReadOnlySpan<double> source, double a) =>
        AddScaled(target, source, -a);
}
