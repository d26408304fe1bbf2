using System;
using ParticlePhysics.Contacts;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Fluids;

// The walls of the fluid: each substep lists, for every fluid particle, the obstacles of the boundary's contact set
// within reach of its ghosts (FluidWall), with their distance and normal where the substep ends. The projection's
// iterations move the particles by little, so each wall is taken as the plane tangent there: d = n . x + c.
public sealed partial class PositionBasedFluid
{
    private readonly ObstacleBroadPhase _obstacles = new();
    private readonly FluidWall _wall;
    private ContactSet? _boundary;
    private int[] _candidates = Array.Empty<int>();
    private double[] _wallFrame = Array.Empty<double>(); // per wall, its normal n and tangents t, b (FluidWall)
    private double[] _wallOffset = Array.Empty<double>(); // per wall, c
    private double[] _wallDistance = Array.Empty<double>(); // per wall, d at the current positions
    private int[] _runParticle = Array.Empty<int>(); // per particle near a wall, its local index
    private int[] _runFirst = Array.Empty<int>(); // and its first wall; its walls run to the next particle's first
    private double[] _runGradient = Array.Empty<double>(); // per particle near a wall, the walls' gradient sum, 3
    private int _walls;
    private int _runs;

    /// <summary>
    /// The contact set whose obstacles bound the fluid (null, the default: none). Near a particle, the inside of its
    /// obstacles counts in its density as fluid at rest (<see cref="FluidWall"/>), so that the fluid is at its rest
    /// density against the walls as inside; the contact set still keeps the particles out of the obstacles by their
    /// radii. The obstacles are read as they are at every substep, so obstacles added later are walls too.
    /// </summary>
    public ContactSet? Boundary
    {
        get => _boundary;
        set => _boundary = value;
    }

    /// <summary>The particle-obstacle pairs within the reach of the particles' ghosts that the last substep found.</summary>
    public int WallCount => _walls;

    // Lists the walls near every fluid particle at the gathered positions, where the obstacles are at time `time`.
    private void FindWalls(double time)
    {
        _walls = 0;
        _runs = 0;
        if (_boundary is not { } boundary || boundary.Obstacles.Count == 0)
        {
            return;
        }

        var obstacles = boundary.Obstacles;
        _obstacles.Update(obstacles, time, time);
        var reach = _wall.Reach;
        var grow = new Vector3d(reach, reach, reach);
        for (var k = 0; k < _count; k++)
        {
            if (_inverse[k] == 0.0)
            {
                continue;
            }

            var at = new Vector3d(_x[3 * k], _x[(3 * k) + 1], _x[(3 * k) + 2]);
            var found = _obstacles.Collect(at - grow, at + grow, boundary.FilterOf(_particles[k]), -1, ref _candidates);
            var first = _walls;
            for (var c = 0; c < found; c++)
            {
                var obstacle = obstacles[_candidates[c]];
                var q = at - obstacle.OffsetAt(time);
                var d = obstacle.Distance(q.X, q.Y, q.Z, out var nx, out var ny, out var nz);
                if (d < reach)
                {
                    AddWall(new Vector3d(nx, ny, nz), d - ((nx * at.X) + (ny * at.Y) + (nz * at.Z)));
                }
            }

            if (_walls > first)
            {
                AddRun(k, first);
            }
        }
    }

    private void AddWall(Vector3d normal, double offset)
    {
        if (_walls == _wallOffset.Length)
        {
            var capacity = Math.Max(64, 2 * _walls);
            Array.Resize(ref _wallFrame, FluidWall.FrameLength * capacity);
            Array.Resize(ref _wallOffset, capacity);
            Array.Resize(ref _wallDistance, capacity);
        }

        UnitVectors.Tangents(normal, out var t, out var b);
        var f = FluidWall.FrameLength * _walls;
        (_wallFrame[f], _wallFrame[f + 1], _wallFrame[f + 2]) = (normal.X, normal.Y, normal.Z);
        (_wallFrame[f + 3], _wallFrame[f + 4], _wallFrame[f + 5]) = (t.X, t.Y, t.Z);
        (_wallFrame[f + 6], _wallFrame[f + 7], _wallFrame[f + 8]) = (b.X, b.Y, b.Z);
        _wallOffset[_walls] = offset;
        _walls++;
    }

    private void AddRun(int particle, int first)
    {
        if (_runs == _runParticle.Length)
        {
            var capacity = Math.Max(64, 2 * _runs);
            Array.Resize(ref _runParticle, capacity);
            Array.Resize(ref _runFirst, capacity);
            Array.Resize(ref _runGradient, 3 * capacity);
        }

        _runParticle[_runs] = particle;
        _runFirst[_runs] = first;
        _runs++;
    }

    // Adds the walls' density and gradient to their particles' sums, at the current positions.
    private void SumWalls()
    {
        for (var r = 0; r < _runs; r++)
        {
            var k = _runParticle[r];
            var first = _runFirst[r];
            var end = r + 1 < _runs ? _runFirst[r + 1] : _walls;
            for (var w = first; w < end; w++)
            {
                var f = FluidWall.FrameLength * w;
                _wallDistance[w] = (_wallFrame[f] * _x[3 * k]) + (_wallFrame[f + 1] * _x[(3 * k) + 1])
                    + (_wallFrame[f + 2] * _x[(3 * k) + 2]) + _wallOffset[w];
            }

            _runGradient[3 * r] = 0.0;
            _runGradient[(3 * r) + 1] = 0.0;
            _runGradient[(3 * r) + 2] = 0.0;
            _density[k] += _wall.Add(_wallDistance, _wallFrame, first, end - first, _runGradient, 3 * r);
            _gradient[3 * k] += _runGradient[3 * r];
            _gradient[(3 * k) + 1] += _runGradient[(3 * r) + 1];
            _gradient[(3 * k) + 2] += _runGradient[(3 * r) + 2];
        }
    }

    // The ghosts have no constraint and do not move: they add w_a (kappa / rho_0) lambda_a G_a to their particle's
    // move, G_a the walls' gradient sum that SumWalls took at the same positions.
    private void MoveByWalls()
    {
        var scale = _kappa / RestDensity;
        for (var r = 0; r < _runs; r++)
        {
            var k = _runParticle[r];
            var f = _inverse[k] * scale * _lambda[k];
            _move[3 * k] += f * _runGradient[3 * r];
            _move[(3 * k) + 1] += f * _runGradient[(3 * r) + 1];
            _move[(3 * k) + 2] += f * _runGradient[(3 * r) + 2];
        }
    }
}
