using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The broad phase between particles and obstacles, which every stage that meets an obstacle asks first
/// (<see cref="ObstacleBroadPhase"/>): the obstacles a particle's box may reach, in index order, filtered by layers.
/// </summary>
public sealed partial class ContactSet
{
    /// <summary>
    /// Fills <c>_candidates</c> with the obstacles after <paramref name="after"/> that a box around
    /// the box of <paramref name="lo"/> and <paramref name="hi"/> grown by <paramref name="reach"/> may touch and that particle
    /// <paramref name="particle"/>'s filter accepts, in increasing order; returns how many.
    /// </summary>
    private int ObstaclesNear(int particle, Vector3d lo, Vector3d hi, double reach, int after)
    {
        var min = new Vector3d(Math.Min(lo.X, hi.X), Math.Min(lo.Y, hi.Y), Math.Min(lo.Z, hi.Z));
        var max = new Vector3d(Math.Max(lo.X, hi.X), Math.Max(lo.Y, hi.Y), Math.Max(lo.Z, hi.Z));
        var grow = new Vector3d(reach, reach, reach);
        var started = BroadPhaseStart();
        var found = _colliders.Collect(min - grow, max + grow, ParticleFilter(particle), after, ref _candidates);
        BroadPhaseEnd(started, 0);
        return found;
    }

    /// <summary>The obstacles' boxes swept over [from, to], which ObstaclesNear reads (timed as the broad phase).</summary>
    private void UpdateObstacleBoxes(double from, double to)
    {
        var started = BroadPhaseStart();
        _colliders.Update(_obstacles, from, to);
        BroadPhaseEnd(started, 0);
    }

    /// <summary>The same around one point.</summary>
    private int ObstaclesNear(int particle, Vector3d at, double reach, int after) => ObstaclesNear(particle, at, at, reach, after);

    /// <summary>For tests: every stage tests every obstacle, as before the broad phase (the same bits, slower).</summary>
    internal bool TestEveryObstacle
    {
        get => _colliders.Disabled;
        set => _colliders.Disabled = value;
    }

    /// <summary>The filter of a particle: its own, or the default.</summary>
    internal CollisionFilter FilterOf(int particle) => ParticleFilter(particle);

    private CollisionFilter ParticleFilter(int particle) =>
        particle < _particleFilters.Length ? _particleFilters[particle] : CollisionFilter.Default;

    /// <summary>What the broad phase between particles drops: the user's pair filter, and the layers once any particle has a filter.</summary>
    private IContactPairFilter? BroadPhaseFilter()
    {
        if (!_anyParticleFilter)
        {
            return PairFilter;
        }

        _layered.Next = PairFilter;
        return _layered;
    }

    /// <summary>
    /// The least distance from the centre within which a particle of <paramref name="radius"/> can be found touching:
    /// the radius, the resting margin and the search's tolerance.
    /// </summary>
    private static double TouchReach(double radius) => (radius * (1.0 + RestingMargin)) + (10.0 * ContactSearch.Tolerance);
}
