using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>Stage 2 of <see cref="ContactSet.Resolve"/>: the particle pairs that may meet within the step.</summary>
public sealed partial class ContactSet
{
    /// <summary>
    /// The candidate pairs of the step: the broad phase (<see cref="SpatialHashGrid"/>) on swept boxes of start and end,
    /// grown by the radius and the path's bulge, then the narrow test (<see cref="MayMeet"/>); pairs of two pinned
    /// particles are left out, as they cannot move.
    /// </summary>
    private void FindSweptPairs(in ConstraintContext context)
    {
        var n = context.Count;
        var duration = context.Dt;
        var x0 = context.StartPositions.ForReading();
        var x1 = context.Positions;
        var inverseMasses = context.InverseMasses.ForReading();
        var radii = context.Radii.ForReading();
        var min = _boxes.Min;
        var max = _boxes.Max;
        var sweep = _boxes.Sweep;
        for (var i = 0; i < n; i++)
        {
            // A cubic departs from its chord by at most A T^2 / 8 (A: the bound on its second derivative); the quarter
            // radius more keeps the pairs that nearly touch at the end for the separation stage.
            var bulge = 0.125 * _paths.AccelerationBound(i, 0.0, duration) * duration * duration;
            var grow = (1.25 * Radius(radii, i)) + bulge;
            sweep[i] = Distance(x0, i, x1, i) + bulge;
            for (var c = 0; c < 3; c++)
            {
                var a = x0[(3 * i) + c];
                var b = x1[(3 * i) + c];
                min[(3 * i) + c] = Math.Min(a, b) - grow;
                max[(3 * i) + c] = Math.Max(a, b) + grow;
            }
        }

        var started = BroadPhaseStart();
        if (!_sweptGrid.TryFindPairs(min, max, n, BroadPhaseFilter(), _maxCandidatePairs))
        {
            RefuseCandidatePairs(n);
        }

        BroadPhaseEnd(started, _sweptGrid.PairCount);

        var first = _sweptGrid.First.ForReading();
        var second = _sweptGrid.Second.ForReading();
        var found = _sweptGrid.PairCount;
        _pairs.Reset(found, DefaultMaxCandidatePairs);
        for (var p = 0; p < found; p++)
        {
            var i = first[p];
            var j = second[p];
            if ((inverseMasses[i] == 0.0 && inverseMasses[j] == 0.0) || !MayMeet(i, j, x0, radii))
            {
                continue; // two pinned particles cannot move; two swept spheres too far apart cannot meet
            }

            _pairs.Add(i, j);
        }

        _log.CandidatePairs = _pairs.Count;
    }

    /// <summary>
    /// The narrow test after the boxes, whose corners let through neighbours up to sqrt(3) times too far: a centre
    /// stays within its sweep (chord plus bulge) of where it started, so two particles can come within 1.25 (r_i + r_j)
    /// of each other only if their start distance is at most that plus both sweeps.
    /// </summary>
    private bool MayMeet(int i, int j, Span<double> x0, Span<double> radii) =>
        Distance(x0, i, x0, j) <= (1.25 * (Radius(radii, i) + Radius(radii, j))) + _boxes.Sweep[i] + _boxes.Sweep[j];

    private void RefuseCandidatePairs(int n)
    {
        _pairs.Clear();
        _log.CandidatePairs = 0;
        throw new InvalidOperationException(
            $"The contact set found more than MaxCandidatePairs = {_maxCandidatePairs} candidate pairs among {n} particles "
            + "(particles heaped within reach of each other): the search stopped there and the step is refused, with "
            + $"nothing changed. Spread the particles out, or raise MaxCandidatePairs (at most {DefaultMaxCandidatePairs}, about 40 bytes a pair).");
    }
}
