using System;

namespace ParticlePhysics.Constraints;

// The projection order: the generator's springs copied, coloured and partitioned when its topology changes, and
// their parameters laid out in that order when they change.
public sealed partial class SpringProjection
{
    // The generator's own layout, copied when its versions change.
    private int[] _pairFirst = Array.Empty<int>();
    private int[] _pairSecond = Array.Empty<int>();
    private double[] _pairParameters = Array.Empty<double>();
    private int[] _anchoredParticle = Array.Empty<int>();
    private double[] _anchoredParameters = Array.Empty<double>();

    /// <summary>Recolours when the springs' topology changed, and recopies their parameters when they changed.</summary>
    private void Refresh(int particles)
    {
        var topology = _springs.TopologyVersion;
        var parameters = _springs.ParameterVersion;
        if (topology == _topologyVersion && parameters == _parameterVersion && particles == _particles)
        {
            return;
        }

        int pairs = _springs.PairCount, anchored = _springs.AnchoredCount;
        var count = pairs + anchored;
        var recolour = topology != _topologyVersion || particles != _particles || count != _count;
        if (recolour)
        {
            _pairFirst = new int[pairs];
            _pairSecond = new int[pairs];
            _pairParameters = new double[3 * pairs];
            _anchoredParticle = new int[anchored];
            _anchoredParameters = new double[6 * anchored];
        }

        _springs.CopyPairs(_pairFirst, _pairSecond, _pairParameters);
        _springs.CopyAnchored(_anchoredParticle, _anchoredParameters);
        for (var p = 0; p < pairs; p++)
        {
            if ((uint)_pairFirst[p] >= (uint)particles || (uint)_pairSecond[p] >= (uint)particles)
            {
                throw new ArgumentException(
                    $"Spring {p} joins particles {_pairFirst[p]} and {_pairSecond[p]}, but the world has {particles}.");
            }

            if (_pairFirst[p] == _pairSecond[p])
            {
                throw new ArgumentException($"Spring {p} joins particle {_pairFirst[p]} to itself: a spring needs two particles.");
            }
        }

        for (var a = 0; a < anchored; a++)
        {
            if ((uint)_anchoredParticle[a] >= (uint)particles)
            {
                throw new ArgumentException(
                    $"Anchored spring {a} holds particle {_anchoredParticle[a]}, but the world has {particles}.");
            }
        }

        if (recolour)
        {
            Recolour(pairs, anchored, particles);
        }

        // The parameters in the projection order (the ends, rest lengths and anchors straight into the hot arrays):
        // the k-th pair spring of _order is _pairs[k's rank among the pairs], and likewise for the anchored ones.
        int nextPair = 0, nextAnchored = 0;
        for (var k = 0; k < count; k++)
        {
            var source = _order[k];
            if (source < pairs)
            {
                var s = nextPair++;
                _pairs[s].First = (uint)_pairFirst[source];
                _pairs[s].Second = (uint)_pairSecond[source];
                _pairs[s].RestLength = _pairParameters[(3 * source) + 1];
                _pairCoefficients[2 * s] = _pairParameters[3 * source];
                _pairCoefficients[(2 * s) + 1] = _pairParameters[(3 * source) + 2];
            }
            else
            {
                var s = nextAnchored++;
                var a = source - pairs;
                _anchored[s].Particle = _anchoredParticle[a];
                _anchored[s].AnchorX = _anchoredParameters[6 * a];
                _anchored[s].AnchorY = _anchoredParameters[(6 * a) + 1];
                _anchored[s].AnchorZ = _anchoredParameters[(6 * a) + 2];
                _anchored[s].RestLength = _anchoredParameters[(6 * a) + 4];
                _anchoredCoefficients[2 * s] = _anchoredParameters[(6 * a) + 3];
                _anchoredCoefficients[(2 * s) + 1] = _anchoredParameters[(6 * a) + 5];
            }
        }

        _undamped = true;
        for (var k = 1; k < _pairCoefficients.Length; k += 2)
        {
            _undamped &= _pairCoefficients[k] == 0.0;
        }

        _preparedStep = double.NaN;
        _count = count;
        _particles = particles;
        _topologyVersion = topology;
        _parameterVersion = parameters;
    }

    /// <summary>
    /// Colours the springs in their own index order (pairs, then anchored with second end -1), lays each colour out as
    /// its pairs followed by its anchored springs, and partitions that colour order into one group per part
    /// (<see cref="ConstraintPartition"/>): <see cref="ProjectionOrder"/>, and the batch, group and phase starts.
    /// </summary>
    private void Recolour(int pairs, int anchored, int particles)
    {
        var count = pairs + anchored;
        var first = new int[count];
        var second = new int[count];
        _pairFirst.AsSpan().CopyTo(first);
        _pairSecond.AsSpan().CopyTo(second);
        for (var a = 0; a < anchored; a++)
        {
            first[pairs + a] = _anchoredParticle[a];
            second[pairs + a] = -1;
        }

        var byColour = new int[count];
        var colourStarts = ConstraintColouring.Colour(first, second, count, particles, byColour);
        var colours = colourStarts.Length - 1;
        var colourOrder = new int[count];
        var next = 0;
        for (var c = 0; c < colours; c++)
        {
            // Stable within the colour: its pairs in index order, then its anchored springs in index order.
            for (var k = colourStarts[c]; k < colourStarts[c + 1]; k++)
            {
                if (byColour[k] < pairs)
                {
                    colourOrder[next++] = byColour[k];
                }
            }

            for (var k = colourStarts[c]; k < colourStarts[c + 1]; k++)
            {
                if (byColour[k] >= pairs)
                {
                    colourOrder[next++] = byColour[k];
                }
            }
        }

        var partition = ConstraintPartition.Build(first, second, count, particles, colourOrder, colourStarts);
        _order = partition.Order;
        _batchStarts = partition.BatchStarts;
        _groupBatchStarts = partition.GroupBatchStarts;
        _groupStarts = partition.GroupStarts;
        _phaseStarts = partition.PhaseStarts;
        _partStarts = partition.PartStarts;
        _colours = colours;

        // Each batch keeps its colour's arrangement (pairs, then anchored springs): its share of each hot array.
        var batches = _batchStarts.Length - 1;
        _pairStarts = new int[batches + 1];
        _anchoredStarts = new int[batches + 1];
        for (var b = 0; b < batches; b++)
        {
            var batchPairs = 0;
            for (var k = _batchStarts[b]; k < _batchStarts[b + 1]; k++)
            {
                batchPairs += _order[k] < pairs ? 1 : 0;
            }

            _pairStarts[b + 1] = _pairStarts[b] + batchPairs;
            _anchoredStarts[b + 1] = _anchoredStarts[b] + (_batchStarts[b + 1] - _batchStarts[b] - batchPairs);
        }

        _pairs = new PairSpring[pairs];
        _anchored = new AnchoredSpring[anchored];
        _pairCoefficients = new double[2 * pairs];
        _anchoredCoefficients = new double[2 * anchored];
    }
}
