using System;
using ParticlePhysics.Numerics;
using ParticlePhysics.Parallel;

namespace ParticlePhysics.Constraints;

/// <summary>
/// The triangles of a membrane (<see cref="IMembraneElements"/>: <c>Forces.TriangleMembrane</c>) as XPBD constraints
/// under the position-based integrator: the world then leaves the membrane out of the forces and this set projects each
/// triangle once per substep. Under the force-based integrators it does nothing: the membrane acts as a force.
/// </summary>
/// <remarks>
/// <para>
/// The Saint Venant-Kirchhoff energy of a triangle is exactly quadratic in its Green strain, so the triangle is one
/// constraint of three components, c = (E_xx, E_yy, 2 E_xy), of stiffness K = A0 [[2 mu + lambda, lambda, 0],
/// [lambda, 2 mu + lambda, 0], [0, 0, mu]] (energy c^T K c / 2), compliance alpha = K^-1, projected as a block
/// (Macklin, Mueller and Chentanez, "XPBD", 2016, its vector form): with F = [F1 F2] and the corners' weights
/// beta_a (<see cref="IMembraneElements.CopyTriangles"/>), grad_a c = (beta_ax F1, beta_ay F2, beta_ax F2 + beta_ay F1),
/// A = sum_a w_a grad_a c grad_a c^T (3 x 3, from the sums P_xx, P_yy, P_xy of w_a beta_a beta_a^T),
/// dlambda = -((1 + gamma) A + alpha / h^2)^-1 (c + gamma grad c . (x - x0)), x_a += w_a grad_a c^T dlambda, with
/// gamma = tau / h for the damping time tau = eta / Y (XPBD's damping with a damping matrix proportional to K). The
/// 3 x 3 system is solved by its cofactors. Stable at any stiffness: with alpha -&gt; 0 it is the rigid projection.
/// </para>
/// <para>
/// The triangles are projected in colour order (<see cref="ElementColouring"/>: no two of a colour share a particle),
/// computed again only when the membrane's topology changes, from flat arrays in that order.
/// </para>
/// </remarks>
public sealed class MembraneProjection : IForceProjection
{
    private const int Stride = 8;

    // Triangles per chunk below which a runner is not worth waking.
    private const int MinTrianglesPerChunk = 128;
    private readonly IMembraneElements _membrane;
    private readonly ColourPass _pass = new();
    private int _topologyVersion = -1;
    private int _parameterVersion = -1;
    private int _particles = -1;
    private Triangle[] _triangles = Array.Empty<Triangle>();
    private int[] _colourStarts = { 0 };
    private double _preparedStep = double.NaN;

    /// <summary>The projection of <paramref name="membrane"/>; add it to the world that holds it with <see cref="ParticleWorld.AddConstraints"/>.</summary>
    public MembraneProjection(IMembraneElements membrane)
    {
        Guard.NotNull(membrane, nameof(membrane));
        _membrane = membrane;
    }

    /// <inheritdoc />
    public IForceGenerator Force => _membrane;

    /// <summary>The number of colours of the triangles' colouring: 0 before the first projection.</summary>
    public int ColourCount => _colourStarts.Length - 1;

    /// <inheritdoc />
    /// <remarks>Nothing: under the force-based integrators the membrane acts as a force.</remarks>
    public void Resolve(in ConstraintContext context)
    {
    }

    /// <inheritdoc />
    /// <remarks>Nothing: the damping is in the projection.</remarks>
    public void SolveVelocities(in ConstraintContext context)
    {
    }

    /// <inheritdoc />
    public void Project(in ConstraintContext context)
    {
        Refresh(context.Count);
        var h = context.Dt;
        if (h != _preparedStep)
        {
            Prepare(h);
        }

        var x = context.Positions;
        var x0 = context.StartPositions.ForReading();
        var w = context.InverseMasses.ForReading();
        if (context.Runner is not { MaxParallelism: > 1 } runner)
        {
            ProjectRange(0, _triangles.Length, x, x0, w);
            return;
        }

        unsafe
        {
            // The spans hold the world's particles, and Refresh checked every corner against their count.
            fixed (double* px = x, px0 = x0, pw = w)
            {
                for (var c = 0; c + 1 < _colourStarts.Length; c++)
                {
                    // The triangles of a colour share no particle: split over the runner, the same bits in any order.
                    int begin = _colourStarts[c], end = _colourStarts[c + 1];
                    var chunks = Math.Min(2 * runner.MaxParallelism, (end - begin) / MinTrianglesPerChunk);
                    if (chunks > 1)
                    {
                        _pass.Set(this, begin, end, px, px0, pw, x.Length, w.Length);
                        runner.Run(_pass, chunks);
                    }
                    else
                    {
                        ProjectRange(begin, end, x, x0, w);
                    }
                }
            }
        }
    }

    private void ProjectRange(int begin, int end, Span<double> x, Span<double> x0, Span<double> w)
    {
        for (var t = begin; t < end; t++)
        {
            ProjectTriangle(ref _triangles[t], x, x0, w);
        }
    }

    private static void ProjectTriangle(ref Triangle t, Span<double> x, Span<double> x0, Span<double> inverseMasses)
    {
        double w0 = inverseMasses[t.First], w1 = inverseMasses[t.Second], w2 = inverseMasses[t.Third];
        if (w0 == 0.0 && w1 == 0.0 && w2 == 0.0)
        {
            return;
        }

        int i0 = 3 * t.First, i1 = 3 * t.Second, i2 = 3 * t.Third;
        double p = t.P, q = t.Q, r = t.R, s = t.S;
        double ax = x[i1] - x[i0], ay = x[i1 + 1] - x[i0 + 1], az = x[i1 + 2] - x[i0 + 2];
        double bx = x[i2] - x[i0], by = x[i2 + 1] - x[i0 + 1], bz = x[i2 + 2] - x[i0 + 2];
        double f1x = (p * ax) + (r * bx), f1y = (p * ay) + (r * by), f1z = (p * az) + (r * bz);
        double f2x = (q * ax) + (s * bx), f2y = (q * ay) + (s * by), f2z = (q * az) + (s * bz);
        var n11 = (f1x * f1x) + (f1y * f1y) + (f1z * f1z);
        var n22 = (f2x * f2x) + (f2y * f2y) + (f2z * f2z);
        var n12 = (f1x * f2x) + (f1y * f2y) + (f1z * f2z);
        double c1 = 0.5 * (n11 - 1.0), c2 = 0.5 * (n22 - 1.0), c3 = n12;
        var gamma = t.Gamma;
        if (gamma != 0.0)
        {
            // grad c . (x - x0): the same F-linear map applied to the corners' moves over the substep.
            double mx = x[i1] - x0[i1] - (x[i0] - x0[i0]), my = x[i1 + 1] - x0[i1 + 1] - (x[i0 + 1] - x0[i0 + 1]), mz = x[i1 + 2] - x0[i1 + 2] - (x[i0 + 2] - x0[i0 + 2]);
            double nx = x[i2] - x0[i2] - (x[i0] - x0[i0]), ny = x[i2 + 1] - x0[i2 + 1] - (x[i0 + 1] - x0[i0 + 1]), nz = x[i2 + 2] - x0[i2 + 2] - (x[i0 + 2] - x0[i0 + 2]);
            double d1x = (p * mx) + (r * nx), d1y = (p * my) + (r * ny), d1z = (p * mz) + (r * nz);
            double d2x = (q * mx) + (s * nx), d2y = (q * my) + (s * ny), d2z = (q * mz) + (s * nz);
            c1 += gamma * ((f1x * d1x) + (f1y * d1y) + (f1z * d1z));
            c2 += gamma * ((f2x * d2x) + (f2y * d2y) + (f2z * d2z));
            c3 += gamma * ((f1x * d2x) + (f1y * d2y) + (f1z * d2z) + (f2x * d1x) + (f2y * d1y) + (f2z * d1z));
        }

        // The corners' weights beta: corner 0 (-(p + r), -(q + s)), corner 1 (p, q), corner 2 (r, s).
        double b0x = -(p + r), b0y = -(q + s);
        var pxx = (w0 * b0x * b0x) + (w1 * p * p) + (w2 * r * r);
        var pyy = (w0 * b0y * b0y) + (w1 * q * q) + (w2 * s * s);
        var pxy = (w0 * b0x * b0y) + (w1 * p * q) + (w2 * r * s);
        var g = 1.0 + gamma;
        var m11 = (g * pxx * n11) + t.Compliance11;
        var m22 = (g * pyy * n22) + t.Compliance11;
        var m12 = (g * pxy * n12) + t.Compliance12;
        var m13 = g * ((pxx * n12) + (pxy * n11));
        var m23 = g * ((pxy * n22) + (pyy * n12));
        var m33 = (g * ((pxx * n22) + (2.0 * pxy * n12) + (pyy * n11))) + t.Compliance33;
        var k11 = (m22 * m33) - (m23 * m23);
        var k12 = (m13 * m23) - (m12 * m33);
        var k13 = (m12 * m23) - (m13 * m22);
        var k22 = (m11 * m33) - (m13 * m13);
        var k23 = (m12 * m13) - (m11 * m23);
        var k33 = (m11 * m22) - (m12 * m12);
        var det = (m11 * k11) + (m12 * k12) + (m13 * k13);
        if (!(det > 0.0) || det > double.MaxValue)
        {
            return; // a collapsed triangle: no direction to correct along
        }

        var inverse = -1.0 / det;
        var l1 = inverse * ((k11 * c1) + (k12 * c2) + (k13 * c3));
        var l2 = inverse * ((k12 * c1) + (k22 * c2) + (k23 * c3));
        var l3 = inverse * ((k13 * c1) + (k23 * c2) + (k33 * c3));

        // x_a += w_a (beta_ax (l1 F1 + l3 F2) + beta_ay (l2 F2 + l3 F1)).
        double ux = (l1 * f1x) + (l3 * f2x), uy = (l1 * f1y) + (l3 * f2y), uz = (l1 * f1z) + (l3 * f2z);
        double vx = (l2 * f2x) + (l3 * f1x), vy = (l2 * f2y) + (l3 * f1y), vz = (l2 * f2z) + (l3 * f1z);

        Move(x, i0, w0, b0x, b0y, ux, uy, uz, vx, vy, vz);
        Move(x, i1, w1, p, q, ux, uy, uz, vx, vy, vz);
        Move(x, i2, w2, r, s, ux, uy, uz, vx, vy, vz);
    }

    private static void Move(Span<double> x, int i, double w, double bx, double by, double ux, double uy, double uz, double vx, double vy, double vz)
    {
        if (w == 0.0)
        {
            return;
        }

        x[i] += w * ((bx * ux) + (by * vx));
        x[i + 1] += w * ((bx * uy) + (by * vy));
        x[i + 2] += w * ((bx * uz) + (by * vz));
    }

    /// <summary>The compliance alpha / h^2 and damping gamma of every triangle for the substep h.</summary>
    private void Prepare(double h)
    {
        var hh = h * h;
        for (var k = 0; k < _triangles.Length; k++)
        {
            ref var t = ref _triangles[k];

            // K^-1 = (1 / A0) [[a, -b, 0], [-b, a, 0], [0, 0, 1 / mu]], a = (2 mu + lambda) / (4 mu (mu + lambda)),
            // b = lambda / (4 mu (mu + lambda)).
            var scale = 1.0 / (t.Area * hh * 4.0 * t.Mu * (t.Mu + t.Lambda));
            t.Compliance11 = scale * ((2.0 * t.Mu) + t.Lambda);
            t.Compliance12 = -scale * t.Lambda;
            t.Compliance33 = 1.0 / (t.Area * hh * t.Mu);
            t.Gamma = t.Tau / h;
        }

        _preparedStep = h;
    }

    /// <summary>Recolours when the triangles changed, and recopies their parameters when those changed.</summary>
    private void Refresh(int particles)
    {
        var topology = _membrane.TopologyVersion;
        var parameters = _membrane.ParameterVersion;
        if (topology == _topologyVersion && parameters == _parameterVersion && particles == _particles)
        {
            return;
        }

        var count = _membrane.TriangleCount;
        var corners = new int[3 * count];
        var values = new double[Stride * count];
        _membrane.CopyTriangles(corners, values);
        for (var k = 0; k < 3 * count; k++)
        {
            if ((uint)corners[k] >= (uint)particles)
            {
                throw new ArgumentException($"Triangle {k / 3} names particle {corners[k]}, but the world has {particles}.");
            }
        }

        var order = new int[count];
        _colourStarts = ElementColouring.Colour(corners, 3, count, particles, order);
        var triangles = new Triangle[count];
        for (var k = 0; k < count; k++)
        {
            var e = order[k];
            var o = Stride * e;
            triangles[k] = new Triangle
            {
                First = corners[3 * e],
                Second = corners[(3 * e) + 1],
                Third = corners[(3 * e) + 2],
                P = values[o],
                Q = values[o + 1],
                R = values[o + 2],
                S = values[o + 3],
                Area = values[o + 4],
                Mu = values[o + 5],
                Lambda = values[o + 6],
                Tau = values[o + 7],
            };
        }

        _triangles = triangles;
        _preparedStep = double.NaN;
        _particles = particles;
        _topologyVersion = topology;
        _parameterVersion = parameters;
    }

    /// <summary>One colour over the runner's chunks: each chunk projects a range of its triangles.</summary>
    private sealed unsafe class ColourPass : IParallelWork
    {
        private MembraneProjection? _owner;
        private double* _x;
        private double* _x0;
        private double* _w;
        private int _coordinates;
        private int _particles;
        private int _begin;
        private int _end;

        public void Set(MembraneProjection owner, int begin, int end, double* x, double* x0, double* w, int coordinates, int particles)
        {
            _owner = owner;
            _begin = begin;
            _end = end;
            _x = x;
            _x0 = x0;
            _w = w;
            _coordinates = coordinates;
            _particles = particles;
        }

        public void Execute(int chunk, int chunkCount)
        {
            var (begin, end) = Chunk.Range(chunk, chunkCount, _end - _begin);
            _owner!.ProjectRange(
                _begin + begin, _begin + end, new Span<double>(_x, _coordinates), new Span<double>(_x0, _coordinates), new Span<double>(_w, _particles));
        }
    }

    /// <summary>A triangle as the projection reads it.</summary>
    private struct Triangle
    {
        public int First;
        public int Second;
        public int Third;
        public double P;
        public double Q;
        public double R;
        public double S;
        public double Area;
        public double Mu;
        public double Lambda;
        public double Tau;
        public double Compliance11; // alpha_11 / h^2 = alpha_22 / h^2
        public double Compliance12;
        public double Compliance33;
        public double Gamma; // tau / h
    }
}
