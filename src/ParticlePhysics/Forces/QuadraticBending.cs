using System;
using System.Runtime.InteropServices;
using ParticlePhysics.Internal;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Forces;

/// <summary>
/// A bending energy quadratic in the positions: elements e, each a few particles v with weights b_kv for up to three
/// components k, E = 1/2 sum_e s_e sum_k |sum_v b_kv x_v|^2 = 1/2 x^T Q x (Q acting alike on x, y and z), so that
/// F = -Q x and the Jacobian df/dx = -Q is constant. The weights are those of a discrete curvature: a rope's second
/// difference (<c>Cloth.RopeBending</c>) or a plate's Hessian per triangle (<c>Cloth.PlateBending</c>); they sum to zero
/// and vanish on straight or flat rest shapes, so rigid motions of the rest shape cost no energy.
/// </summary>
/// <remarks>
/// Why quadratic: for nearly isometric bending (cloth and ropes barely stretch) the curvature energy of a flat sheet or
/// a straight rope is quadratic in the positions (Bergou, Wardetzky, Harmon, Zorin and Grinspun, "A quadratic bending
/// model for inextensible surfaces", 2006), so the forces are a sparse matrix-vector product, implicit Euler's Jacobian
/// is that matrix and never changes, and xpbd projects each element as a linear constraint. Q is assembled once from
/// the elements (compressed rows, each row's columns in increasing order, each entry summed in element order) when they
/// change; a force evaluation is then one pass over the rows, each row computed on its own, so a runner splits the rows
/// and gets the same bits. The energy is rotation invariant (each x_i . x_j is) but its rest shape is flat: a mesh that
/// is curved as given is a flat sheet bent into that shape.
/// </remarks>
public sealed class QuadraticBending : IForceGenerator, IPotentialEnergy, IBoundForce, IJacobianCouplings, IAppendOnlyCouplings, IBendingElements
{
    /// <summary>The most particles of one element: 6 (a triangle and the far corners of its three neighbours).</summary>
    public const int MaxParticles = 6;

    /// <summary>The most components of one element: 3 (a symmetric 2 x 2 curvature).</summary>
    public const int MaxComponents = 3;

    private const int WeightStride = MaxParticles * MaxComponents;

    // Rows per chunk below which a runner is not worth waking.
    private const int MinRowsPerChunk = 2048;

    private readonly ParticleWorld _system;
    private readonly RowPass _pass = new();
    private int[] _particles = Array.Empty<int>();
    private double[] _weights = Array.Empty<double>();
    private double[] _stiffness = Array.Empty<double>();
    private int _count;
    private int _topologyVersion;
    private int _parameterVersion;

    // Q in compressed rows, the diagonal entry included; the couplings are the entries above the diagonal, in row order.
    private int _assembledTopology = -1;
    private int _assembledParameters = -1;
    private int _rows;
    private int[] _rowStarts = { 0 };
    private int[] _columns = Array.Empty<int>();
    private double[] _values = Array.Empty<double>();
    private double[] _diagonal = Array.Empty<double>();
    private int[] _upper = Array.Empty<int>();
    private int[] _upperRow = Array.Empty<int>();
    private double _positionScale;
    private IParallelRunner? _runner; // the runner of the last Linearize, for the products that follow
    private LinearizationStamp _linearized;

    /// <summary>An empty bending energy for the particles of <paramref name="system"/>.</summary>
    public QuadraticBending(ParticleWorld system)
    {
        Guard.NotNull(system, nameof(system));
        _system = system;
    }

    /// <summary>The number of elements.</summary>
    public int Count => _count;

    /// <inheritdoc />
    int IBendingElements.ElementCount => _count;

    /// <inheritdoc />
    public int TopologyVersion => _topologyVersion;

    /// <inheritdoc />
    public int ParameterVersion => _parameterVersion;

    object? IBoundForce.World => _system;

    /// <summary>
    /// Adds an element: <paramref name="particles"/> (2 to 6 distinct existing particles), its weights
    /// (<paramref name="weights"/>: one row of particles.Length values per component, 1 to 3 rows) and its stiffness s.
    /// </summary>
    /// <returns>The element's index.</returns>
    public int Add(ReadOnlySpan<int> particles, ReadOnlySpan<double> weights, double stiffness)
    {
        _system.ThrowIfStepping();
        var ends = particles.ForReading();
        var b = weights.ForReading();
        var n = particles.Length;
        if (n < 2 || n > MaxParticles)
        {
            throw new ArgumentException($"An element joins 2 to {MaxParticles} particles; got {n}.", nameof(particles));
        }

        if (weights.Length % n != 0 || weights.Length / n < 1 || weights.Length / n > MaxComponents)
        {
            throw new ArgumentException(
                $"weights must hold 1 to {MaxComponents} rows of {n} values (one per particle); it holds {weights.Length}.", nameof(weights));
        }

        for (var v = 0; v < n; v++)
        {
            Guard.ParticleIndex(ends[v], _system.Count, nameof(particles));
            for (var u = 0; u < v; u++)
            {
                if (ends[u] == ends[v])
                {
                    throw new ArgumentException($"An element names particle {ends[v]} twice.", nameof(particles));
                }
            }
        }

        for (var k = 0; k < weights.Length; k++)
        {
            Guard.Finite(b[k], nameof(weights));
        }

        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        if (_count == _stiffness.Length)
        {
            var capacity = Math.Max(8, 2 * _count);
            Array.Resize(ref _particles, MaxParticles * capacity);
            Array.Resize(ref _weights, WeightStride * capacity);
            Array.Resize(ref _stiffness, capacity);
        }

        var e = _count;
        _particles.AsSpan(MaxParticles * e, MaxParticles).Fill(-1);
        _weights.AsSpan(WeightStride * e, WeightStride).Clear();
        particles.CopyTo(_particles.AsSpan(MaxParticles * e, n));
        for (var k = 0; k < weights.Length / n; k++)
        {
            weights.Slice(k * n, n).CopyTo(_weights.AsSpan((WeightStride * e) + (k * MaxParticles), n));
        }

        _stiffness[e] = stiffness;
        _count++;
        _topologyVersion++;
        return e;
    }

    /// <summary>The stiffness s of an element.</summary>
    public double GetStiffness(int element)
    {
        CheckElement(element);
        return _stiffness[element];
    }

    /// <summary>Changes the stiffness s of an element (a finite number &gt;= 0).</summary>
    public void SetStiffness(int element, double stiffness)
    {
        _system.ThrowIfStepping();
        CheckElement(element);
        Guard.NonNegativeFinite(stiffness, nameof(stiffness));
        _stiffness[element] = stiffness;
        _parameterVersion++;
    }

    /// <summary>Multiplies every element's stiffness by <paramref name="factor"/> (a finite number &gt;= 0): a new rigidity.</summary>
    public void ScaleStiffness(double factor)
    {
        _system.ThrowIfStepping();
        Guard.NonNegativeFinite(factor, nameof(factor));
        for (var e = 0; e < _count; e++)
        {
            var scaled = _stiffness[e] * factor;
            Guard.NonNegativeFinite(scaled, nameof(factor));
        }

        for (var e = 0; e < _count; e++)
        {
            _stiffness[e] *= factor;
        }

        _parameterVersion++;
    }

    /// <inheritdoc />
    public void CopyElements(Span<int> particles, Span<double> weights, Span<double> stiffness)
    {
        _particles.AsSpan(0, MaxParticles * _count).CopyTo(particles);
        _weights.AsSpan(0, WeightStride * _count).CopyTo(weights);
        _stiffness.AsSpan(0, _count).CopyTo(stiffness);
    }

    /// <summary>The entry Q_ij of the assembled matrix (0 where i and j share no element).</summary>
    public double MatrixEntry(int i, int j)
    {
        Assemble();
        if ((uint)i >= (uint)_rows)
        {
            return 0.0;
        }

        for (var k = _rowStarts[i]; k < _rowStarts[i + 1]; k++)
        {
            if (_columns[k] == j)
            {
                return _values[k];
            }
        }

        return 0.0;
    }

    /// <inheritdoc />
    public void AddForces(in ParticleState state, Span<double> forces)
    {
        Assemble();
        CheckSizes(state.Positions.Length, forces.Length);
        Multiply(state.Positions, forces, -1.0, state.Runner);
    }

    /// <inheritdoc />
    /// <remarks>
    /// 1/2 x^T Q x, summed element by element as s / 2 sum_k |c_k|^2 (never negative, and without the cancellation of
    /// the assembled form: a rigid motion of the rest shape gives its rounding only).
    /// </remarks>
    public double PotentialEnergy(in ParticleState state)
    {
        Assemble();
        CheckSizes(state.Positions.Length, state.Positions.Length);
        var x = state.Positions.ForReading();
        var sum = 0.0;
        for (var e = 0; e < _count; e++)
        {
            var element = 0.0;
            for (var k = 0; k < MaxComponents; k++)
            {
                double cx = 0.0, cy = 0.0, cz = 0.0;
                for (var v = 0; v < MaxParticles; v++)
                {
                    var i = _particles[(MaxParticles * e) + v];
                    if (i < 0)
                    {
                        break;
                    }

                    var b = _weights[(WeightStride * e) + (k * MaxParticles) + v];
                    cx += b * x[3 * i];
                    cy += b * x[(3 * i) + 1];
                    cz += b * x[(3 * i) + 2];
                }

                element += (cx * cx) + (cy * cy) + (cz * cz);
            }

            sum += 0.5 * _stiffness[e] * element;
        }

        return sum;
    }

    /// <inheritdoc />
    /// <remarks>J = -a Q (no velocity term); (df/dx) v = -Q v.</remarks>
    public void Linearize(
        in ParticleState state, double positionScale, double velocityScale, Span<double> positionJacobianTimesVelocity)
    {
        Assemble();
        CheckSizes(state.Velocities.Length, positionJacobianTimesVelocity.Length);
        _positionScale = positionScale;
        _runner = state.Runner;
        Multiply(state.Velocities, positionJacobianTimesVelocity, -1.0, state.Runner);
        _linearized.Record(_count, _assembledParameters);
    }

    /// <inheritdoc />
    public void AddJacobianProduct(ReadOnlySpan<double> w, Span<double> result)
    {
        CheckLinearized();
        CheckSizes(w.Length, result.Length);
        Multiply(w, result, -_positionScale, _runner);
    }

    /// <inheritdoc />
    public void AddDiagonalBlocks(Span<double> blocks)
    {
        CheckLinearized();
        for (var i = 0; i < _rows; i++)
        {
            JacobianBlocks.AddIsotropic(blocks, i, -_positionScale * _diagonal[i]);
        }
    }

    /// <inheritdoc />
    public int CouplingCount
    {
        get
        {
            Assemble();
            return _upper.Length;
        }
    }

    /// <inheritdoc />
    public void WriteCouplings(Span<int> first, Span<int> second)
    {
        Assemble();
        for (var c = 0; c < _upper.Length; c++)
        {
            first[c] = _upperRow[c];
            second[c] = _columns[_upper[c]];
        }
    }

    /// <inheritdoc />
    public void AddCouplingBlocks(Span<double> destination, ReadOnlySpan<int> forwardBlock, ReadOnlySpan<int> backwardBlock)
    {
        CheckLinearized();
        var forward = forwardBlock.ForReading();
        var backward = backwardBlock.ForReading();
        for (var c = 0; c < _upper.Length; c++)
        {
            var s = -_positionScale * _values[_upper[c]];
            if (forward[c] >= 0)
            {
                AddIsotropicBlock(destination, forward[c], s);
            }

            if (backward[c] >= 0)
            {
                AddIsotropicBlock(destination, backward[c], s);
            }
        }
    }

    private static void AddIsotropicBlock(Span<double> destination, int block, double s)
    {
        var o = 9 * block;
        destination[o] += s;
        destination[o + 4] += s;
        destination[o + 8] += s;
    }

    private void CheckLinearized()
    {
        _linearized.Check(nameof(QuadraticBending), _count, _parameterVersion);
        if (_assembledTopology != _topologyVersion || _assembledParameters != _parameterVersion)
        {
            throw new InvalidOperationException(
                "QuadraticBending changed since it was linearised: call Linearize again after adding or retuning elements.");
        }
    }

    private void CheckElement(int element)
    {
        if ((uint)element >= (uint)_count)
        {
            throw new ArgumentOutOfRangeException(
                nameof(element), element, $"element must name an existing element, 0 to {_count - 1}; got {element}.");
        }
    }

    private void CheckSizes(int input, int output)
    {
        var needed = 3 * _rows;
        if (input < needed || output < needed)
        {
            throw new ArgumentException(
                $"QuadraticBending needs buffers of at least {needed} values (3 per particle it names); got {input} and {output}.");
        }
    }

    /// <summary>result += scale Q x, row by row (over the runner's chunks of rows when there are enough).</summary>
    private unsafe void Multiply(ReadOnlySpan<double> x, Span<double> result, double scale, IParallelRunner? runner)
    {
        fixed (double* xp = &MemoryMarshal.GetReference(x), rp = result, values = _values)
        fixed (int* starts = _rowStarts, columns = _columns)
        {
            var chunks = runner is { MaxParallelism: > 1 } ? Math.Min(2 * runner.MaxParallelism, _rows / MinRowsPerChunk) : 1;
            if (chunks > 1)
            {
                _pass.Set(xp, rp, values, starts, columns, scale, _rows);
                runner!.Run(_pass, chunks);
                return;
            }

            MultiplyRows(xp, rp, values, starts, columns, scale, 0, _rows);
        }
    }

    private static unsafe void MultiplyRows(
        double* x, double* result, double* values, int* starts, int* columns, double scale, int begin, int end)
    {
        for (var i = begin; i < end; i++)
        {
            double sx = 0.0, sy = 0.0, sz = 0.0;
            for (int k = starts[i], last = starts[i + 1]; k < last; k++)
            {
                var xj = x + (3L * columns[k]);
                var q = values[k];
                sx += q * xj[0];
                sy += q * xj[1];
                sz += q * xj[2];
            }

            var r = result + (3L * i);
            r[0] += scale * sx;
            r[1] += scale * sy;
            r[2] += scale * sz;
        }
    }

    /// <summary>
    /// Q = sum_e s_e sum_k b_k b_k^T in compressed rows, when the elements changed since the last assembly: every
    /// element's contributions listed, sorted by (row, column, element), and summed in that order.
    /// </summary>
    private void Assemble()
    {
        if (_assembledTopology == _topologyVersion && _assembledParameters == _parameterVersion)
        {
            return;
        }

        var rows = 0;
        var terms = 0;
        for (var e = 0; e < _count; e++)
        {
            var n = 0;
            for (var v = 0; v < MaxParticles && _particles[(MaxParticles * e) + v] >= 0; v++)
            {
                n++;
                rows = Math.Max(rows, _particles[(MaxParticles * e) + v] + 1);
            }

            terms += n * n;
        }

        var keys = new Entry[terms];
        var t = 0;
        for (var e = 0; e < _count; e++)
        {
            for (var a = 0; a < MaxParticles; a++)
            {
                var i = _particles[(MaxParticles * e) + a];
                if (i < 0)
                {
                    break;
                }

                for (var b = 0; b < MaxParticles; b++)
                {
                    var j = _particles[(MaxParticles * e) + b];
                    if (j < 0)
                    {
                        break;
                    }

                    var q = 0.0;
                    for (var k = 0; k < MaxComponents; k++)
                    {
                        var row = (WeightStride * e) + (k * MaxParticles);
                        q += _weights[row + a] * _weights[row + b];
                    }

                    keys[t++] = new Entry(i, j, e, _stiffness[e] * q);
                }
            }
        }

        Array.Sort(keys);
        var rowStarts = new int[rows + 1];
        var columns = new int[terms];
        var values = new double[terms];
        var diagonal = new double[rows];
        var entries = 0;
        var upper = 0;
        for (var k = 0; k < terms; k++)
        {
            var key = keys[k];
            if (k > 0 && keys[k - 1].Row == key.Row && keys[k - 1].Column == key.Column)
            {
                values[entries - 1] += key.Value;
                continue;
            }

            columns[entries] = key.Column;
            values[entries] = key.Value;
            entries++;
            rowStarts[key.Row + 1] = entries;
            upper += key.Column > key.Row ? 1 : 0;
        }

        // Rows without entries (particles no element names) start where the row before them ends.
        for (var i = 0; i < rows; i++)
        {
            rowStarts[i + 1] = Math.Max(rowStarts[i + 1], rowStarts[i]);
        }

        Array.Resize(ref columns, entries);
        Array.Resize(ref values, entries);
        var upperEntries = new int[upper];
        var upperRow = new int[upper];
        var u = 0;
        for (var i = 0; i < rows; i++)
        {
            for (var k = rowStarts[i]; k < rowStarts[i + 1]; k++)
            {
                if (columns[k] == i)
                {
                    diagonal[i] = values[k];
                }
                else if (columns[k] > i)
                {
                    upperEntries[u] = k;
                    upperRow[u++] = i;
                }
            }
        }

        _rows = rows;
        _rowStarts = rowStarts;
        _columns = columns;
        _values = values;
        _diagonal = diagonal;
        _upper = upperEntries;
        _upperRow = upperRow;
        _assembledTopology = _topologyVersion;
        _assembledParameters = _parameterVersion;
    }

    /// <summary>One contribution s_e b_i . b_j to Q_ij, ordered by row, column, then element (a total order: no ties).</summary>
    private readonly struct Entry : IComparable<Entry>
    {
        public Entry(int row, int column, int element, double value)
        {
            Row = row;
            Column = column;
            Element = element;
            Value = value;
        }

        public int Row { get; }

        public int Column { get; }

        public int Element { get; }

        public double Value { get; }

        public int CompareTo(Entry other) =>
            Row != other.Row ? Row.CompareTo(other.Row)
            : Column != other.Column ? Column.CompareTo(other.Column)
            : Element.CompareTo(other.Element);
    }

    /// <summary>The product over the runner's chunks, each a range of rows.</summary>
    private sealed unsafe class RowPass : IParallelWork
    {
        private double* _x;
        private double* _result;
        private double* _values;
        private int* _starts;
        private int* _columns;
        private double _scale;
        private int _rows;

        public void Set(double* x, double* result, double* values, int* starts, int* columns, double scale, int rows)
        {
            _x = x;
            _result = result;
            _values = values;
            _starts = starts;
            _columns = columns;
            _scale = scale;
            _rows = rows;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _rows);
            MultiplyRows(_x, _result, _values, _starts, _columns, _scale, begin, end);
        }
    }
}
