using System;
using System.Runtime.CompilerServices;
using System.Runtime.InteropServices;

namespace ParticlePhysics.Numerics;

/// <summary>
/// How the core reads a <see cref="ReadOnlySpan{T}"/> so that it runs on Mono, Unity's runtime.
/// </summary>
/// <remarks>
/// Mono's corlib declares ReadOnlySpan&lt;T&gt;'s indexer and GetPinnableReference as returning <c>ref T</c>; the
/// netstandard2.1 reference assembly that the core is compiled against says <c>ref readonly T</c>, encoded as a
/// modreq(InAttribute) on the return type. Call sites with that modreq do not bind on Mono (MissingMethodException),
/// so the core never calls them: it indexes a read-only span through a <see cref="Span{T}"/> over the same memory,
/// which it only reads, and pins one with <c>fixed (double* p = &amp;MemoryMarshal.GetReference(span))</c>. Both are
/// free on CoreCLR (the JIT treats them as the span's own reference and length). A test reads the built assembly and
/// fails on any such call (MonoCompatibilityTests).
/// </remarks>
internal static class ReadOnlySpans
{
    /// <summary>The same memory as an indexable span, for reading only: the core never writes through it.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static Span<T> ForReading<T>(this ReadOnlySpan<T> span) =>
        MemoryMarshal.CreateSpan(ref MemoryMarshal.GetReference(span), span.Length);
}
