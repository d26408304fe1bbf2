using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// What each obstacle received from the particles since the step began (<see cref="ContactSet.ReactionOf"/>): the
/// total impulse and the angular impulse about its <see cref="Obstacle.ReactionPoint"/>, kept aside at the start of a
/// step so that a failed step shows the last committed one again.
/// </summary>
internal sealed class ColliderReactions
{
    private double[] _values = Array.Empty<double>();
    private double[] _saved = Array.Empty<double>();
    private int _count;
    private int _savedCount;

    /// <summary>Zero for <paramref name="obstacles"/> obstacles (arrays grow to the most obstacles seen, then are kept).</summary>
    public void Clear(int obstacles)
    {
        if (_values.Length < 6 * obstacles)
        {
            _values = new double[6 * Math.Max(obstacles, 4)];
        }

        _values.AsSpan(0, 6 * obstacles).Clear();
        _count = obstacles;
    }

    /// <summary>The reaction of obstacle <paramref name="k"/> (zero when the last step had fewer obstacles).</summary>
    public ColliderReaction Of(int k) =>
        k < _count
            ? new ColliderReaction(
                new Vector3d(_values[6 * k], _values[(6 * k) + 1], _values[(6 * k) + 2]),
                new Vector3d(_values[(6 * k) + 3], _values[(6 * k) + 4], _values[(6 * k) + 5]))
            : default;

    /// <summary>
    /// Obstacle k receives the impulse <paramref name="impulse"/> at <paramref name="point"/>; <paramref name="about"/>
    /// is its reaction point where it is at that time.
    /// </summary>
    public void Add(int k, Vector3d impulse, Vector3d point, Vector3d about)
    {
        if (k >= _count)
        {
            return;
        }

        var o = 6 * k;
        var angular = Vector3d.Cross(point - about, impulse);
        _values[o] += impulse.X;
        _values[o + 1] += impulse.Y;
        _values[o + 2] += impulse.Z;
        _values[o + 3] += angular.X;
        _values[o + 4] += angular.Y;
        _values[o + 5] += angular.Z;
    }

    /// <summary>Keeps the reactions aside (a copy that grows with them).</summary>
    public void Save()
    {
        if (_saved.Length < _values.Length)
        {
            _saved = new double[_values.Length];
        }

        _values.AsSpan(0, 6 * _count).CopyTo(_saved);
        _savedCount = _count;
    }

    /// <summary>Shows the reactions kept aside by <see cref="Save"/> again.</summary>
    public void Restore()
    {
        _count = _savedCount;
        _saved.AsSpan(0, 6 * _count).CopyTo(_values);
    }
}
