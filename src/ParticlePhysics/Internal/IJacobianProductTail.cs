using System;

namespace ParticlePhysics.Internal;

/// <summary>
/// A linearisable system whose Jacobian product ends with a uniform term, result[k] += c w[k] on every coordinate
/// after the terms that couple particles (a cloth's drag after its springs), which a solver can apply inside a pass of
/// its own over the same vectors instead of a pass of the term's own: the same operation on each value in the same
/// order, so the same bits.
/// </summary>
/// <remarks>
/// Why: the term's own pass would run on the calling thread alone, once per product, while a runner's other threads
/// wait.
/// </remarks>
internal interface IJacobianProductTail
{
    /// <summary>
    /// True when, after the last linearisation, the product's last term that does anything is result[k] += c w[k] on
    /// every coordinate, with <paramref name="coefficient"/> c; false when there is no such tail.
    /// </summary>
    bool TryGetUniformTail(out double coefficient);

    /// <summary>
    /// result += J w without the tail that <see cref="TryGetUniformTail"/> found: every term before it, in order (the
    /// terms after it do nothing). The caller adds c w itself, after these terms.
    /// </summary>
    void AddJacobianProductBeforeTail(ReadOnlySpan<double> w, Span<double> result);
}
