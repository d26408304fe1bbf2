using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// A list of (particle, obstacle) contacts: the separation's particles near an obstacle at the end of the step, which
/// its Gauss-Seidel passes visit and from which its shock pass ranks the particles. Grows by doubling and is kept.
/// </summary>
internal sealed class ObstacleContactList
{
    private int[] _particle = Array.Empty<int>();
    private int[] _obstacle = Array.Empty<int>();

    /// <summary>The number of contacts.</summary>
    public int Count { get; private set; }

    /// <summary>The particle of contact <paramref name="c"/>.</summary>
    public int Particle(int c) => _particle[c];

    /// <summary>The obstacle of contact <paramref name="c"/>.</summary>
    public int Obstacle(int c) => _obstacle[c];

    /// <summary>Empties the list.</summary>
    public void Clear() => Count = 0;

    /// <summary>Appends a contact.</summary>
    public void Add(int particle, int obstacle)
    {
        if (Count == _particle.Length)
        {
            var capacity = Math.Max(64, 2 * Count);
            Array.Resize(ref _particle, capacity);
            Array.Resize(ref _obstacle, capacity);
        }

        _particle[Count] = particle;
        _obstacle[Count] = obstacle;
        Count++;
    }
}
