using System;
using System.Runtime.CompilerServices;

namespace ParticlePhysics.Forces;

/// <summary>
/// The per-spring arithmetic of the spring network's Jacobian, shared by the sequential loops and the parallel
/// passes so that both give the same bits. A linearised spring is stored as (ux, uy, uz, s, t): its block
/// a df_i/dx_i + b df_i/dv_i = s I + t u u^T (see <see cref="SpringNetwork"/> for the derivation).
/// </summary>
internal static unsafe class SpringLinearization
{
    /// <summary>
    /// Linearises the spring between a and b (parameters k, L, c at <paramref name="parameters"/>) into
    /// <paramref name="linear"/>, and writes df/dx (v_a - v_b) at end a, -(iso dv + axial (u . dv) u), into y.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void Pair(
        double* x, double* v, long a, long b, double* parameters, double positionScale, double velocityScale,
        double* linear, double* y)
    {
        double k = parameters[0], restLength = parameters[1], c = parameters[2];
        double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
        var lengthSquared = (dx * dx) + (dy * dy) + (dz * dz);
        double axial, iso;
        if (lengthSquared == 0.0)
        {
            // No direction: a zero-rest-length spring is still -k I; a spring with a rest length exerts no force here.
            iso = restLength == 0.0 ? k : 0.0;
            axial = 0.0;
            linear[0] = linear[1] = linear[2] = linear[4] = 0.0;
            linear[3] = -positionScale * iso;
        }
        else
        {
            var length = Math.Sqrt(lengthSquared);
            var inverse = 1.0 / length;
            var transverse = Math.Max(0.0, 1.0 - (restLength * inverse));
            linear[0] = dx * inverse;
            linear[1] = dy * inverse;
            linear[2] = dz * inverse;
            linear[3] = -positionScale * k * transverse;
            linear[4] = -((positionScale * k * (1.0 - transverse)) + (velocityScale * c));
            axial = k * (1.0 - transverse);
            iso = k * transverse;
        }

        double dvx = v[a] - v[b], dvy = v[a + 1] - v[b + 1], dvz = v[a + 2] - v[b + 2];
        var along = axial * ((linear[0] * dvx) + (linear[1] * dvy) + (linear[2] * dvz));
        y[0] = -((iso * dvx) + (along * linear[0]));
        y[1] = -((iso * dvy) + (along * linear[1]));
        y[2] = -((iso * dvz) + (along * linear[2]));
    }

    /// <summary>
    /// <see cref="Pair"/> and the spring's force in one evaluation of its direction: writes the linearisation into
    /// <paramref name="linear"/>, df/dx (v_a - v_b) at end a into <paramref name="y"/>, and into
    /// <paramref name="force"/> the vector (k (l - L) + c (v_a - v_b) . u) u that the force loop subtracts at end a and
    /// adds at end b (zero when l = 0). Every value is computed by the same operations as in <see cref="Pair"/> and in
    /// <see cref="SpringNetwork.AddForces"/>, so the bits are theirs. <paramref name="roots"/> points at the spring's l
    /// in the block <see cref="SpringLengths.Compute"/> wrote, its 1 / l <see cref="SpringLengths.Block"/> values on.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void PairWithForce(
        double* x, double* v, long a, long b, double* parameters, double positionScale, double velocityScale,
        double* roots, double* linear, double* y, double* force)
    {
        double k = parameters[0], restLength = parameters[1], c = parameters[2];
        double dx = x[a] - x[b], dy = x[a + 1] - x[b + 1], dz = x[a + 2] - x[b + 2];
        double dvx = v[a] - v[b], dvy = v[a + 1] - v[b + 1], dvz = v[a + 2] - v[b + 2];
        var length = roots[0];
        if (length == 0.0)
        {
            // As Pair, operation for operation (so that signed zeros agree too), and no force: the force loop adds a
            // zero vector there.
            var iso0 = restLength == 0.0 ? k : 0.0;
            linear[0] = linear[1] = linear[2] = linear[4] = 0.0;
            linear[3] = -positionScale * iso0;
            var along0 = 0.0 * ((linear[0] * dvx) + (linear[1] * dvy) + (linear[2] * dvz));
            y[0] = -((iso0 * dvx) + (along0 * linear[0]));
            y[1] = -((iso0 * dvy) + (along0 * linear[1]));
            y[2] = -((iso0 * dvz) + (along0 * linear[2]));
            force[0] = force[1] = force[2] = 0.0;
            return;
        }

        var inverse = roots[SpringLengths.Block];
        var transverse = Math.Max(0.0, 1.0 - (restLength * inverse));
        double ux = dx * inverse, uy = dy * inverse, uz = dz * inverse;
        linear[0] = ux;
        linear[1] = uy;
        linear[2] = uz;
        linear[3] = -positionScale * k * transverse;
        linear[4] = -((positionScale * k * (1.0 - transverse)) + (velocityScale * c));
        var axial = k * (1.0 - transverse);
        var iso = k * transverse;
        var closing = (ux * dvx) + (uy * dvy) + (uz * dvz);
        var along = axial * closing;
        y[0] = -((iso * dvx) + (along * ux));
        y[1] = -((iso * dvy) + (along * uy));
        y[2] = -((iso * dvz) + (along * uz));

        // The force loop's closing speed is (dv . u) with the products the other way round: the same bits.
        var magnitude = (k * (length - restLength)) + (c * closing);
        force[0] = magnitude * ux;
        force[1] = magnitude * uy;
        force[2] = magnitude * uz;
    }

    /// <summary>
    /// Adds into the diagonal block of each particle in [begin, end) the blocks s I + t u u^T of its springs, in
    /// increasing spring order (<see cref="SpringIncidence"/>'s rows), summed in locals and stored once: the same
    /// additions in the same order as adding each spring's block into both its ends spring by spring, so the same bits,
    /// with 9 stores per particle instead of 9 read-modify-writes per spring end.
    /// </summary>
    public static void GatherBlocks(double* blocks, double* linear, int* start, int* incident, int begin, int end)
    {
        for (var i = begin; i < end; i++)
        {
            var block = blocks + (9L * i);
            double b0 = block[0], b1 = block[1], b2 = block[2], b3 = block[3], b4 = block[4];
            double b5 = block[5], b6 = block[6], b7 = block[7], b8 = block[8];
            if (SameBits(b1, b3) && SameBits(b2, b6) && SameBits(b5, b7))
            {
                // A symmetric block (as the blocks start, cleared) stays symmetric bit for bit: each pair of mirrored
                // values starts equal and gets the same additions. So six sums, and the mirror copied.
                for (var e = start[i]; e < start[i + 1]; e++)
                {
                    var q = linear + (5L * (incident[e] >> 1));
                    double ux = q[0], uy = q[1], uz = q[2], s = q[3], t = q[4];
                    b0 += s + (t * ux * ux);
                    b1 += t * ux * uy;
                    b2 += t * ux * uz;
                    b4 += s + (t * uy * uy);
                    b5 += t * uy * uz;
                    b8 += s + (t * uz * uz);
                }

                block[0] = b0;
                block[1] = block[3] = b1;
                block[2] = block[6] = b2;
                block[4] = b4;
                block[5] = block[7] = b5;
                block[8] = b8;
                continue;
            }

            for (var e = start[i]; e < start[i + 1]; e++)
            {
                var q = linear + (5L * (incident[e] >> 1));
                double ux = q[0], uy = q[1], uz = q[2], s = q[3], t = q[4];
                double xx = s + (t * ux * ux), yy = s + (t * uy * uy), zz = s + (t * uz * uz);
                double xy = t * ux * uy, xz = t * ux * uz, yz = t * uy * uz;
                b0 += xx;
                b1 += xy;
                b2 += xz;
                b3 += xy;
                b4 += yy;
                b5 += yz;
                b6 += xz;
                b7 += yz;
                b8 += zz;
            }

            block[0] = b0;
            block[1] = b1;
            block[2] = b2;
            block[3] = b3;
            block[4] = b4;
            block[5] = b5;
            block[6] = b6;
            block[7] = b7;
            block[8] = b8;
        }
    }

    /// <summary>
    /// Subtracts s I + t u u^T (symmetric) from the 3 x 3 blocks at <paramref name="first"/> and
    /// <paramref name="second"/>, or from <paramref name="first"/> alone when <paramref name="once"/>.
    /// </summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public static void SubtractBlock(double* first, double* second, double* linear, bool once = false)
    {
        double ux = linear[0], uy = linear[1], uz = linear[2], iso = linear[3], t = linear[4];
        double xx = iso + (t * ux * ux), yy = iso + (t * uy * uy), zz = iso + (t * uz * uz);
        double xy = t * ux * uy, xz = t * ux * uz, yz = t * uy * uz;
        first[0] -= xx;
        first[1] -= xy;
        first[2] -= xz;
        first[3] -= xy;
        first[4] -= yy;
        first[5] -= yz;
        first[6] -= xz;
        first[7] -= yz;
        first[8] -= zz;
        if (once)
        {
            return;
        }

        second[0] -= xx;
        second[1] -= xy;
        second[2] -= xz;
        second[3] -= xy;
        second[4] -= yy;
        second[5] -= yz;
        second[6] -= xz;
        second[7] -= yz;
        second[8] -= zz;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    private static bool SameBits(double a, double b) => BitConverter.DoubleToInt64Bits(a) == BitConverter.DoubleToInt64Bits(b);
}
