using ParticlePhysics.Parallel;

namespace ParticlePhysics.Constraints;

// The two ways a pass goes over the world's runner: a phase of several groups, or one large batch in ranges.
public sealed partial class SpringProjection
{
    /// <summary>One phase of several groups over the runner's chunks: each chunk projects a range of whole groups.</summary>
    private sealed unsafe class GroupPass : IParallelWork
    {
        private SpringProjection? _owner;
        private PairSpring* _pairs;
        private AnchoredSpring* _anchored;
        private double* _x;
        private double* _x0;
        private double* _w;
        private int _groupBegin;
        private int _groupEnd;

        public void Set(
            SpringProjection owner, int groupBegin, int groupEnd, PairSpring* pairs, AnchoredSpring* anchored, double* x,
            double* x0, double* w)
        {
            _owner = owner;
            _groupBegin = groupBegin;
            _groupEnd = groupEnd;
            _pairs = pairs;
            _anchored = anchored;
            _x = x;
            _x0 = x0;
            _w = w;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _groupEnd - _groupBegin);
            _owner!.ProjectGroups(_groupBegin + begin, _groupBegin + end, _pairs, _anchored, _x, _x0, _w);
        }
    }

    /// <summary>One batch over the runner's chunks: each chunk projects its share of the batch's pairs and anchored springs.</summary>
    private sealed unsafe class BatchPass : IParallelWork
    {
        private PairSpring* _pairs;
        private AnchoredSpring* _anchored;
        private double* _x;
        private double* _x0;
        private double* _w;
        private int _pairBegin;
        private int _pairEnd;
        private int _anchoredBegin;
        private int _anchoredEnd;
        private bool _undamped;

        public void Set(
            PairSpring* pairs, int pairBegin, int pairEnd, AnchoredSpring* anchored, int anchoredBegin, int anchoredEnd,
            double* x, double* x0, double* w, bool undamped)
        {
            _undamped = undamped;
            _pairs = pairs;
            _pairBegin = pairBegin;
            _pairEnd = pairEnd;
            _anchored = anchored;
            _anchoredBegin = anchoredBegin;
            _anchoredEnd = anchoredEnd;
            _x = x;
            _x0 = x0;
            _w = w;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (pairBegin, pairEnd) = Chunk.Range(chunk, chunkCount, _pairEnd - _pairBegin);
            if (_undamped)
            {
                ProjectUndampedPairs(_pairs, _pairBegin + pairBegin, _pairBegin + pairEnd, _x, _w);
            }
            else
            {
                ProjectPairs(_pairs, _pairBegin + pairBegin, _pairBegin + pairEnd, _x, _x0, _w);
            }

            var (anchoredBegin, anchoredEnd) = Chunk.Range(chunk, chunkCount, _anchoredEnd - _anchoredBegin);
            ProjectAnchored(_anchored, _anchoredBegin + anchoredBegin, _anchoredBegin + anchoredEnd, _x, _x0, _w);
        }
    }
}
