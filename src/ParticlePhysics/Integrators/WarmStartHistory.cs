using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Integrators;

/// <summary>
/// Implicit Euler's memory between steps: the velocity changes dv of the last <see cref="Depth"/> committed steps,
/// newest first, and for the newest of them the products A dv with their own steps' matrices (b - r at the end of
/// each solve), which the next solve's start is made from; the scratch pair the step under way solves into; and their
/// form as <see cref="IStatefulIntegrator"/> state, so that a restored run continues bit for bit.
/// </summary>
/// <remarks>
/// A step writes only the scratch pair; <see cref="Commit"/> makes it the newest step and the oldest pair becomes the
/// next scratch (references rotated, nothing copied or allocated once every buffer exists); <see cref="Discard"/>
/// forgets it. So a step that fails leaves the history as it was.
/// State: a header, then the k known steps' dv newest first, then the p newest steps' products (3 N values each),
/// p &lt;= k &lt;= <see cref="Depth"/>. The header is k + 3 p while k &lt;= 2, which is the whole format of the library
/// before the history was deeper than two steps (so those states read both ways, and a state without products has
/// p = 0), and 16 + k + 8 p for k = 3 or 4.
/// </remarks>
internal sealed class WarmStartHistory
{
    /// <summary>
    /// The steps remembered: four, where the iterations the start saves stop falling (c54a830's docs/benchmarks.md,
    /// "The warm start from the last four steps").
    /// </summary>
    public const int Depth = 4;

    private const int DeepHeader = 16;

    private readonly double[]?[] _dv = new double[Depth][];
    private readonly double[]?[] _product = new double[Depth][];
    private double[]? _scratchDv;
    private double[]? _scratchProduct;
    private int _pendingKnown = -1; // the steps known once the pending step is committed; -1: none pending
    private int _pendingProducts;

    /// <summary>The committed steps whose dv is known, 0 to <see cref="Depth"/>.</summary>
    public int Known { get; private set; }

    /// <summary>How many of the newest known steps have their product too (at most <see cref="Known"/>).</summary>
    public int KnownProducts { get; private set; }

    /// <summary>The length of the known vectors (3 values per particle), or -1 when none is known.</summary>
    public int Length { get; private set; } = -1;

    /// <summary>The values of the state: the header and the known vectors.</summary>
    public int StateLength => 1 + ((Known + KnownProducts) * Math.Max(0, Length));

    /// <summary>The dv of the step <paramref name="age"/> steps back (0: the last), when <paramref name="age"/> &lt; <see cref="Known"/>.</summary>
    public double[] Dv(int age) => _dv[age]!;

    /// <summary>The product A dv of that step, when <paramref name="age"/> &lt; <see cref="KnownProducts"/>.</summary>
    public double[] Product(int age) => _product[age]!;

    /// <summary>
    /// The scratch dv and product, <paramref name="n"/> values each, for the step under way; allocates every buffer of
    /// the history at the first step (a null one is no part of the committed state), so that later steps allocate
    /// nothing.
    /// </summary>
    public (double[] Dv, double[] Product) Scratch(int n)
    {
        _scratchDv = StepChecks.Sized(_scratchDv, n);
        _scratchProduct = StepChecks.Sized(_scratchProduct, n);
        for (var age = 0; age < Depth; age++)
        {
            _dv[age] ??= new double[n];
            _product[age] ??= new double[n];
        }

        return (_scratchDv, _scratchProduct);
    }

    /// <summary>The scratch pair is the step under way's: <paramref name="known"/> steps known after it, the newest <paramref name="products"/> with products.</summary>
    public void SetPending(int known, int products)
    {
        _pendingKnown = known;
        _pendingProducts = products;
    }

    /// <summary>Forgets the step under way, if any.</summary>
    public void Discard() => _pendingKnown = -1;

    /// <summary>Makes the pending step the newest: every pair moves one step back and the oldest becomes the scratch.</summary>
    public void Commit()
    {
        if (_pendingKnown < 0)
        {
            return;
        }

        var oldestDv = _dv[Depth - 1];
        var oldestProduct = _product[Depth - 1];
        for (var age = Depth - 1; age > 0; age--)
        {
            _dv[age] = _dv[age - 1];
            _product[age] = _product[age - 1];
        }

        _dv[0] = _scratchDv;
        _product[0] = _scratchProduct;
        _scratchDv = oldestDv;
        _scratchProduct = oldestProduct;
        Known = _pendingKnown;
        KnownProducts = _pendingProducts;
        Length = _dv[0]!.Length;
        _pendingKnown = -1;
    }

    /// <summary>Writes the state (exactly <see cref="StateLength"/> values).</summary>
    public void WriteState(Span<double> destination)
    {
        if (destination.Length != StateLength)
        {
            throw new ArgumentException(
                $"destination must hold exactly {StateLength} values; it holds {destination.Length}.", nameof(destination));
        }

        destination[0] = Known <= 2 ? Known + (3 * KnownProducts) : DeepHeader + Known + (8 * KnownProducts);
        for (var v = 0; v < Known + KnownProducts; v++)
        {
            StateVector(v).AsSpan(0, Length).CopyTo(destination.Slice(1 + (v * Length)));
        }
    }

    /// <summary>Reads a state written by <see cref="WriteState"/> (or by the library before the deeper history), and forgets any pending step.</summary>
    public void ReadState(ReadOnlySpan<double> source)
    {
        var values = source.ForReading();
        var (known, products) = Decode(source.Length > 0 ? values[0] : -1.0);
        var vectorCount = Math.Max(0, known) + products;
        var valid = known >= 0
            && (vectorCount == 0 ? source.Length == 1 : (source.Length - 1) % (3 * vectorCount) == 0 && source.Length > 1)
            && DoubleChecks.FirstNonFinite(source) < 0;
        if (!valid)
        {
            throw new ArgumentException(
                "An implicit-euler state is a header, k + 3 p for k <= 2 or 16 + k + 8 p for k = 3 or 4 (k steps known, "
                + $"up to {Depth}, and p <= k of them with their products), followed by k + p vectors of 3 finite values "
                + $"per particle; got {source.Length} values starting with {(source.Length > 0 ? Guard.Format(values[0]) : "nothing")}.",
                nameof(source));
        }

        _pendingKnown = -1;
        Known = known;
        KnownProducts = products;
        Length = vectorCount == 0 ? -1 : (source.Length - 1) / vectorCount;
        for (var v = 0; v < vectorCount; v++)
        {
            ref var vector = ref StateVector(v);
            vector = StepChecks.Sized(vector, Length);
            source.Slice(1 + (v * Length), Length).CopyTo(vector);
        }
    }

    /// <summary>(k, p) of a header, or (-1, 0) when no state has it.</summary>
    private static (int Known, int Products) Decode(double header)
    {
        if (header is 0.0 or 1.0 or 2.0 or 4.0 or 5.0 or 8.0)
        {
            return ((int)header % 3, (int)header / 3);
        }

        var deep = header - DeepHeader;
        if (deep >= 0.0 && deep < 64.0 && deep == Math.Floor(deep))
        {
            int known = (int)deep % 8, products = (int)deep / 8;
            if (known is 3 or 4 && products <= known)
            {
                return (known, products);
            }
        }

        return (-1, 0);
    }

    /// <summary>Vector <paramref name="v"/> of the state, in its order: the known steps' dv, newest first, then the known products.</summary>
    private ref double[]? StateVector(int v) => ref v < Known ? ref _dv[v] : ref _product[v - Known];
}
