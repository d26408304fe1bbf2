using System;
using System.Collections.Generic;
using System.Globalization;
using System.Linq;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The <c>preconditioners</c> mode: which preconditioner would cut implicit Euler's iterations enough to pay for
/// itself. It takes the real system of one step of the n x n cloth (after <c>--frames</c> steps at 60 Hz, 1e-3): the
/// right-hand side and A = M - J on the free coordinates, column by column from the library's own products, then
/// runs textbook preconditioned conjugate gradients from zero with candidate preconditioners, built as plain sparse
/// and dense matrices, and prints the iterations to 1e-3 and 1e-6 of |b| and the products with A each iteration costs.
/// </summary>
/// <remarks>
/// An experiment, not the solver: slow (the coarse levels are solved exactly by dense Cholesky, 40 s at n = 64), and
/// the aggregates are the grid's 2 x 2 squares instead of the library's matching (the same sizes on a square cloth).
/// Every candidate shares the library's fine-level smoother, block Jacobi on each particle's 3 x 3 block. The
/// conjugate gradients take Polak and Ribiere's beta, (z1 . (r1 - r0)) / (z0 . r0), which is the textbook one for a
/// fixed symmetric preconditioner and keeps the two non-symmetric candidates (one smoothing sweep on one side of the
/// coarse correction) converging. Results and what they decided: docs/benchmarks.md, "Stronger preconditioners".
/// </remarks>
internal static class PreconditionerLab
{
    public static int Run(string[] args)
    {
        var n = int.Parse(Program.Option(args, "--n") ?? "32", CultureInfo.InvariantCulture);
        var frames = int.Parse(Program.Option(args, "--frames") ?? "30", CultureInfo.InvariantCulture);
        var cloth = new ClothFixture(n);
        var ie = new ImplicitEuler { Tolerance = 1e-3 };
        const double h = 1.0 / 60;
        for (var f = 0; f < frames; f++)
        {
            cloth.System.Step(ie, h);
        }

        var sys = (ILinearizableSystem)cloth.System;
        var state = cloth.System.State.ToArray();
        var n3 = sys.CoordinateCount;
        var x0 = state.AsSpan(0, n3).ToArray();
        var v0 = state.AsSpan(n3, n3).ToArray();
        var jw = new double[n3];
        var blocks = new double[3 * n3];
        var f0 = sys.AccumulateForcesAndLinearize(cloth.System.Time + h, x0, v0, h * h, h, UserForceTreatment.Explicit, jw, blocks).ToArray();
        var masses = sys.Masses.ToArray();
        var inv = sys.InverseMasses.ToArray();

        // The free coordinates (a pinned particle's dv is 0).
        var dofOf = new int[n3];
        var free = new List<int>();
        for (var c = 0; c < n3; c++)
        {
            dofOf[c] = inv[c / 3] == 0 ? -1 : free.Count;
            if (dofOf[c] >= 0)
            {
                free.Add(c);
            }
        }

        var m = free.Count;
        var b = new double[m];
        for (var k = 0; k < m; k++)
        {
            var c = free[k];
            b[k] = h * (f0[c] + (h * jw[c]));
        }

        // A = M - J on the free coordinates, column by column: A e_c = M e_c - J e_c.
        var rows = new List<(int Col, double Val)>[m];
        for (var k = 0; k < m; k++)
        {
            rows[k] = new List<(int, double)>();
        }

        var e = new double[n3];
        var y = new double[n3];
        for (var k = 0; k < m; k++)
        {
            var c = free[k];
            e[c] = 1;
            Array.Clear(y);
            sys.AddJacobianProduct(e, y);
            e[c] = 0;
            for (var r = 0; r < n3; r++)
            {
                var val = -y[r] + (r == c ? masses[c / 3] : 0.0);
                if (val != 0 && dofOf[r] >= 0)
                {
                    rows[dofOf[r]].Add((k, val));
                }
            }
        }

        var a = new Csr(rows);
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture,
            $"n = {n}, the step after {frames} frames: {m} free coordinates, {a.Values.Length} non-zeros in A, |b| = {Norm(b):G4}"));

        // The particle of each free coordinate; the aggregates are the grid's 2 x 2 squares (p0: coordinate -> coarse one).
        int ParticleOf(int k) => free[k] / 3;
        int Agg(int p, int size) => ((p / n) / size * ((n + size - 1) / size)) + ((p % n) / size);
        var half = (n + 1) / 2;
        var aggCount = half * half;
        var p0 = new int[m];
        for (var k = 0; k < m; k++)
        {
            p0[k] = (3 * Agg(ParticleOf(k), 2)) + (free[k] % 3);
        }

        var bj = BlockInverse(a, m, k => ParticleOf(k));
        var aggBj = BlockInverse(a, m, k => Agg(ParticleOf(k), 2));
        var coarse = Galerkin(a, p0, 3 * aggCount);

        Func<double[], double[]> jacobi = r => bj.Apply(r);
        Func<double[], double[]> additive = r => Add(bj.Apply(r), Prolong(coarse.Solve(Restrict(r, p0, 3 * aggCount)), p0));
        Func<double[], double[]> additiveAgg = r => Add(aggBj.Apply(r), Prolong(coarse.Solve(Restrict(r, p0, 3 * aggCount)), p0));
        Func<double[], double[]> multiplicative = r =>
        {
            var z = bj.Apply(r);
            var r1 = Sub(r, a.Multiply(z));
            z = Add(z, Prolong(coarse.Solve(Restrict(r1, p0, 3 * aggCount)), p0));
            var r2 = Sub(r, a.Multiply(z));
            return Add(z, bj.Apply(r2));
        };

        Func<double[], double[]> preSmoothOnly = r =>
        {
            var z = bj.Apply(r);
            var r1 = Sub(r, a.Multiply(z));
            return Add(z, Prolong(coarse.Solve(Restrict(r1, p0, 3 * aggCount)), p0));
        };
        Func<double[], double[]> coarseThenSmooth = r =>
        {
            var z = Prolong(coarse.Solve(Restrict(r, p0, 3 * aggCount)), p0);
            var r1 = Sub(r, a.Multiply(z));
            return Add(z, bj.Apply(r1));
        };

        // Smoothed aggregation: P = (I - omega D^-1 A) P0 (P^T r and P e each need a product with A per iteration).
        var omega = double.Parse(Program.Option(args, "--omega") ?? "0.6", CultureInfo.InvariantCulture);
        var sa = SmoothedProlongation(a, bj, p0, 3 * aggCount, omega);
        var saCoarse = Galerkin(a, sa, 3 * aggCount);
        Func<double[], double[]> additiveSa = r => Add(bj.Apply(r), sa.Multiply(saCoarse.Solve(sa.MultiplyTransposed(r, 3 * aggCount))));

        // Overlapping patches: the 3 x 3 particles from each aggregate's first corner (stride 2), solved exactly and summed.
        var patches = new List<int[]>();
        for (var pr = 0; pr < n; pr += 2)
        {
            for (var pc = 0; pc < n; pc += 2)
            {
                var dofs = new List<int>();
                for (var k = 0; k < m; k++)
                {
                    int p = ParticleOf(k), row = p / n, col = p % n;
                    if (row >= pr && row <= pr + 2 && col >= pc && col <= pc + 2)
                    {
                        dofs.Add(k);
                    }
                }

                patches.Add(dofs.ToArray());
            }
        }

        var schwarz = new BlockSet(a, patches);
        Func<double[], double[]> additiveSchwarz = r => Add(schwarz.Apply(r), Prolong(coarse.Solve(Restrict(r, p0, 3 * aggCount)), p0));

        // The candidates, with the products with the fine A that an iteration costs (the iteration's own, A p, included).
        Console.WriteLine("| preconditioner | products with A per iteration | iterations to 1e-3 | iterations to 1e-6 |");
        Console.WriteLine("| --- | ---: | ---: | ---: |");
        foreach (var (name, products, pre) in new (string, int, Func<double[], double[]>)[]
        {
            ("block Jacobi", 1, jacobi),
            ("additive two-level (the library's form), exact coarse", 1, additive),
            ("additive, 2 x 2 aggregate blocks as the smoother", 1, additiveAgg),
            ("additive, overlapping 3 x 3 patches as the smoother", 1, additiveSchwarz),
            (string.Create(CultureInfo.InvariantCulture, $"additive, smoothed aggregation (omega {omega})"), 3, additiveSa),
            ("multiplicative: smooth, coarse, smooth", 3, multiplicative),
            ("smooth, then coarse (not symmetric)", 2, preSmoothOnly),
            ("coarse, then smooth (not symmetric)", 2, coarseThenSmooth),
        })
        {
            var (i3, i6) = Pcg(a, b, pre);
            Console.WriteLine(string.Create(CultureInfo.InvariantCulture, $"| {name} | {products} | {i3} | {i6} |"));
        }

        return 0;
    }

    /// <summary>Preconditioned conjugate gradients from 0: the iterations to |r| &lt;= 1e-3 |b| and to 1e-6 |b| (-1: not in 400).</summary>
    private static (int, int) Pcg(Csr a, double[] b, Func<double[], double[]> pre)
    {
        var m = b.Length;
        var x = new double[m];
        var r = (double[])b.Clone();
        var z = pre(r);
        var p = (double[])z.Clone();
        var rz = Dot(r, z);
        var bn = Norm(b);
        int i3 = -1, i6 = -1;
        for (var it = 1; it <= 400; it++)
        {
            var ap = a.Multiply(p);
            var alpha = rz / Dot(p, ap);
            var rOld = (double[])r.Clone();
            for (var k = 0; k < m; k++)
            {
                x[k] += alpha * p[k];
                r[k] -= alpha * ap[k];
            }

            var rel = Norm(r) / bn;
            if (i3 < 0 && rel <= 1e-3)
            {
                i3 = it;
            }

            if (rel <= 1e-6)
            {
                i6 = it;
                break;
            }

            z = pre(r);
            var rzNew = Dot(r, z);
            var beta = (rzNew - Dot(rOld, z)) / rz;
            rz = rzNew;
            for (var k = 0; k < m; k++)
            {
                p[k] = z[k] + (beta * p[k]);
            }
        }

        return (i3, i6);
    }

    private static double Dot(double[] u, double[] v)
    {
        var s = 0.0;
        for (var i = 0; i < u.Length; i++)
        {
            s += u[i] * v[i];
        }

        return s;
    }

    private static double Norm(double[] u) => Math.Sqrt(Dot(u, u));

    private static double[] Add(double[] u, double[] v) => u.Select((x, i) => x + v[i]).ToArray();

    private static double[] Sub(double[] u, double[] v) => u.Select((x, i) => x - v[i]).ToArray();

    private static double[] Restrict(double[] r, int[] p0, int coarse)
    {
        var c = new double[coarse];
        for (var k = 0; k < r.Length; k++)
        {
            c[p0[k]] += r[k];
        }

        return c;
    }

    private static double[] Prolong(double[] c, int[] p0) => p0.Select(j => c[j]).ToArray();

    private static Dense Galerkin(Csr a, int[] p0, int coarse)
    {
        var d = new double[coarse, coarse];
        for (var i = 0; i < a.Rows; i++)
        {
            for (var k = a.Start[i]; k < a.Start[i + 1]; k++)
            {
                d[p0[i], p0[a.Cols[k]]] += a.Values[k];
            }
        }

        return new Dense(d);
    }

    private static Dense Galerkin(Csr a, Csr p, int coarse)
    {
        // P^T A P by columns of P.
        var d = new double[coarse, coarse];
        var pt = p.Transpose(coarse);
        for (var j = 0; j < coarse; j++)
        {
            var col = new double[p.Rows];
            for (var k = pt.Start[j]; k < pt.Start[j + 1]; k++)
            {
                col[pt.Cols[k]] = pt.Values[k];
            }

            var apj = a.Multiply(col);
            var c = p.MultiplyTransposed(apj, coarse);
            for (var i = 0; i < coarse; i++)
            {
                d[i, j] = c[i];
            }
        }

        return new Dense(d);
    }

    private static Csr SmoothedProlongation(Csr a, BlockSet bj, int[] p0, int coarse, double omega)
    {
        // Column j of P0 is the indicator of aggregate dof j; P e_j = e_j - omega D^-1 A e_j, built by columns.
        var rows = new List<(int, double)>[a.Rows];
        for (var i = 0; i < a.Rows; i++)
        {
            rows[i] = new List<(int, double)>();
        }

        var members = new List<int>[coarse];
        for (var j = 0; j < coarse; j++)
        {
            members[j] = new List<int>();
        }

        for (var k = 0; k < p0.Length; k++)
        {
            members[p0[k]].Add(k);
        }

        for (var j = 0; j < coarse; j++)
        {
            var col = new double[a.Rows];
            foreach (var k in members[j])
            {
                col[k] = 1;
            }

            var smoothed = bj.Apply(a.Multiply(col));
            for (var i = 0; i < a.Rows; i++)
            {
                var v = col[i] - (omega * smoothed[i]);
                if (v != 0)
                {
                    rows[i].Add((j, v));
                }
            }
        }

        return new Csr(rows);
    }

    private static BlockSet BlockInverse(Csr a, int m, Func<int, int> group)
    {
        var groups = new Dictionary<int, List<int>>();
        for (var k = 0; k < m; k++)
        {
            var g = group(k);
            if (!groups.TryGetValue(g, out var list))
            {
                groups[g] = list = new List<int>();
            }

            list.Add(k);
        }

        return new BlockSet(a, groups.Values.Select(l => l.ToArray()).ToList());
    }

    /// <summary>z = sum over the blocks of R^T A_block^-1 R r: block Jacobi for disjoint blocks, additive Schwarz for overlapping ones.</summary>
    private sealed class BlockSet
    {
        private readonly List<int[]> _dofs;
        private readonly List<Dense> _factors;

        public BlockSet(Csr a, List<int[]> dofs)
        {
            _dofs = dofs.Where(d => d.Length > 0).ToList();
            _factors = _dofs.Select(d => new Dense(a.Sub(d))).ToList();
        }

        public double[] Apply(double[] r)
        {
            var z = new double[r.Length];
            for (var g = 0; g < _dofs.Count; g++)
            {
                var d = _dofs[g];
                var local = _factors[g].Solve(d.Select(k => r[k]).ToArray());
                for (var i = 0; i < d.Length; i++)
                {
                    z[d[i]] += local[i];
                }
            }

            return z;
        }
    }

    private sealed class Csr
    {
        public Csr(List<(int Col, double Val)>[] rows)
        {
            Rows = rows.Length;
            Start = new int[Rows + 1];
            for (var i = 0; i < Rows; i++)
            {
                rows[i].Sort((x, y) => x.Col.CompareTo(y.Col));
                Start[i + 1] = Start[i] + rows[i].Count;
            }

            Cols = rows.SelectMany(r => r.Select(t => t.Col)).ToArray();
            Values = rows.SelectMany(r => r.Select(t => t.Val)).ToArray();
        }

        public int Rows { get; }

        public int[] Start { get; }

        public int[] Cols { get; }

        public double[] Values { get; }

        public double[] Multiply(double[] x)
        {
            var y = new double[Rows];
            for (var i = 0; i < Rows; i++)
            {
                var s = 0.0;
                for (var k = Start[i]; k < Start[i + 1]; k++)
                {
                    s += Values[k] * x[Cols[k]];
                }

                y[i] = s;
            }

            return y;
        }

        public double[] MultiplyTransposed(double[] x, int columns)
        {
            var y = new double[columns];
            for (var i = 0; i < Rows; i++)
            {
                for (var k = Start[i]; k < Start[i + 1]; k++)
                {
                    y[Cols[k]] += Values[k] * x[i];
                }
            }

            return y;
        }

        public Csr Transpose(int columns)
        {
            var rows = new List<(int, double)>[columns];
            for (var j = 0; j < columns; j++)
            {
                rows[j] = new List<(int, double)>();
            }

            for (var i = 0; i < Rows; i++)
            {
                for (var k = Start[i]; k < Start[i + 1]; k++)
                {
                    rows[Cols[k]].Add((i, Values[k]));
                }
            }

            return new Csr(rows);
        }

        public double[,] Sub(int[] dofs)
        {
            var index = new Dictionary<int, int>();
            for (var i = 0; i < dofs.Length; i++)
            {
                index[dofs[i]] = i;
            }

            var d = new double[dofs.Length, dofs.Length];
            for (var i = 0; i < dofs.Length; i++)
            {
                for (var k = Start[dofs[i]]; k < Start[dofs[i] + 1]; k++)
                {
                    if (index.TryGetValue(Cols[k], out var j))
                    {
                        d[i, j] = Values[k];
                    }
                }
            }

            return d;
        }
    }

    /// <summary>A dense symmetric positive definite matrix, factorised (Cholesky) for solves.</summary>
    private sealed class Dense
    {
        private readonly double[,] _l;
        private readonly int _n;

        public Dense(double[,] a)
        {
            _n = a.GetLength(0);
            _l = new double[_n, _n];
            for (var j = 0; j < _n; j++)
            {
                var s = a[j, j];
                for (var k = 0; k < j; k++)
                {
                    s -= _l[j, k] * _l[j, k];
                }

                if (!(s > 0))
                {
                    throw new InvalidOperationException($"not positive definite at {j}: {s}");
                }

                _l[j, j] = Math.Sqrt(s);
                for (var i = j + 1; i < _n; i++)
                {
                    var t = a[i, j];
                    for (var k = 0; k < j; k++)
                    {
                        t -= _l[i, k] * _l[j, k];
                    }

                    _l[i, j] = t / _l[j, j];
                }
            }
        }

        public double[] Solve(double[] b)
        {
            var y = (double[])b.Clone();
            for (var i = 0; i < _n; i++)
            {
                for (var k = 0; k < i; k++)
                {
                    y[i] -= _l[i, k] * y[k];
                }

                y[i] /= _l[i, i];
            }

            for (var i = _n - 1; i >= 0; i--)
            {
                for (var k = i + 1; k < _n; k++)
                {
                    y[i] -= _l[k, i] * y[k];
                }

                y[i] /= _l[i, i];
            }

            return y;
        }
    }
}
