using System;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Forces;

/// <summary>
/// Which springs meet at each particle, in increasing spring order (compressed rows), and the parallel pass that
/// gathers per-spring vectors into per-particle sums in that order. The sequential spring loops scatter spring s into
/// both ends in increasing s; a particle that gathers its springs in increasing order does the same additions in the
/// same order, so the parallel passes give the sequential loop's bits (x - y equals x + (-y) exactly).
/// </summary>
internal sealed unsafe class SpringIncidence
{
    private readonly GatherPass _gather = new();

    // For particle i, entries Start[i] .. Start[i + 1] - 1 of Incident hold its springs in increasing order, encoded
    // as 2 s for a first end and 2 s + 1 for a second end.
    private int[] _start = Array.Empty<int>();
    private int[] _incident = Array.Empty<int>();
    private int _indexedSprings = -1;
    private int _indexedParticles = -1;

    public int[] Start => _start;

    public int[] Incident => _incident;

    /// <summary>Rebuilds the rows when the springs or particles changed in number (springs are only ever added).</summary>
    public void Update(ForceElements pairs, int particleCount)
    {
        if (_indexedSprings == pairs.Count && _indexedParticles == particleCount)
        {
            return;
        }

        var start = new int[particleCount + 1];
        for (var s = 0; s < pairs.Count; s++)
        {
            start[pairs.First[s] + 1]++;
            start[pairs.Second[s] + 1]++;
        }

        for (var i = 0; i < particleCount; i++)
        {
            start[i + 1] += start[i];
        }

        var incident = new int[2 * pairs.Count];
        var fill = (int[])start.Clone();
        for (var s = 0; s < pairs.Count; s++)
        {
            incident[fill[pairs.First[s]]++] = 2 * s;
            incident[fill[pairs.Second[s]]++] = (2 * s) + 1;
        }

        _start = start;
        _incident = incident;
        _indexedSprings = pairs.Count;
        _indexedParticles = particleCount;
    }

    /// <summary>
    /// target[i] (3 values per particle) gets, in increasing spring order, each incident spring's 3-vector from
    /// <paramref name="perSpring"/>: added at a first end and subtracted at a second when
    /// <paramref name="firstEndAdds"/>, the other way round otherwise.
    /// </summary>
    public void Gather(double* target, double* perSpring, bool firstEndAdds, IParallelRunner runner, int chunks)
    {
        fixed (int* start = _start, incident = _incident)
        {
            _gather.Set(target, perSpring, start, incident, _indexedParticles, firstEndAdds);
            runner.Run(_gather, chunks);
        }
    }

    private sealed class GatherPass : IParallelWork
    {
        private double* _target;
        private double* _perSpring;
        private int* _start;
        private int* _incident;
        private int _particles;
        private bool _firstEndAdds;

        public void Set(double* target, double* perSpring, int* start, int* incident, int particles, bool firstEndAdds)
        {
            _target = target;
            _perSpring = perSpring;
            _start = start;
            _incident = incident;
            _particles = particles;
            _firstEndAdds = firstEndAdds;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _particles);
            // The encoding's low bit is 1 for a second end: that end adds when first ends subtract, and vice versa.
            var addsWhen = _firstEndAdds ? 0 : 1;
            for (var i = begin; i < end; i++)
            {
                var f = _target + (3 * i);
                double fx = f[0], fy = f[1], fz = f[2];
                for (var e = _start[i]; e < _start[i + 1]; e++)
                {
                    var code = _incident[e];
                    var sf = _perSpring + (3 * (code >> 1));
                    if ((code & 1) == addsWhen)
                    {
                        fx += sf[0];
                        fy += sf[1];
                        fz += sf[2];
                    }
                    else
                    {
                        fx -= sf[0];
                        fy -= sf[1];
                        fz -= sf[2];
                    }
                }

                f[0] = fx;
                f[1] = fy;
                f[2] = fz;
            }
        }
    }
}
