using System;

namespace ParticlePhysics.Bodies;

/// <summary>
/// The rotation R of the polar decomposition A = R S of a 3 x 3 matrix, by the iteration of Müller, Bender, Chentanez
/// and Macklin ("A Robust Method to Extract the Rotational Part of Deformations", 2016), warm-started from the last
/// one: R is turned by exp(omega) with omega = sum_i r_i x a_i / (|sum_i r_i . a_i| + eps) over the columns r_i of R
/// and a_i of A, until the turn is below 1e-15 rad or 24 iterations have run. Where it can, the step is Newton's
/// instead: linearising sum_i (r_i + omega x r_i) x a_i = 0 gives (tr(B) 1 - B) omega = sum_i r_i x a_i with
/// B = sum_i r_i a_i^T, whose matrix is R (tr(S) 1 - S) R^T near the answer, positive definite, so the iteration
/// converges quadratically rather than at Müller's linear rate, whose ratio grows with the spread of S's eigenvalues (a
/// body much longer than it is thick converges slowly); Müller's step, tr(B) 1 in place of the matrix, is kept where its
/// determinant is not positive (far from the answer, or an inverted cluster).
/// </summary>
/// <remarks>
/// The fixed point has sum_i r_i x a_i = 0, that is R^T A symmetric: R is the polar factor when R^T A is positive
/// definite, which holds for a warm start within a quarter turn of it. Unlike an eigen-decomposition or a Newton
/// iteration of (R + R^-T) / 2 it never fails on a flat or inverted cluster: it returns the nearest rotation it reaches.
/// A rigid cluster's exact shape gives omega of rounding size at once, so it costs one iteration in free flight.
/// </remarks>
internal static class RotationExtraction
{
    public const int MaxIterations = 24;
    private const double Converged = 1e-15;

    /// <summary>The rotation of A (row-major a00..a22), starting from <paramref name="start"/>.</summary>
    public static Quaternion4d Extract(
        double a00, double a01, double a02, double a10, double a11, double a12, double a20, double a21, double a22, Quaternion4d start)
    {
        var c0 = new Vector3d(a00, a10, a20);
        var c1 = new Vector3d(a01, a11, a21);
        var c2 = new Vector3d(a02, a12, a22);

        // eps relative to A's size, so that the iteration does not depend on the units of mass and length.
        var eps = 1e-12 * (c0.Length + c1.Length + c2.Length);
        if (!(eps > 0.0))
        {
            return start;
        }

        var q = start;
        for (var k = 0; k < MaxIterations; k++)
        {
            var r0 = q.Rotate(new Vector3d(1.0, 0.0, 0.0));
            var r1 = q.Rotate(new Vector3d(0.0, 1.0, 0.0));
            var r2 = q.Rotate(new Vector3d(0.0, 0.0, 1.0));
            var torque = Vector3d.Cross(r0, c0) + Vector3d.Cross(r1, c1) + Vector3d.Cross(r2, c2);
            var trace = Vector3d.Dot(r0, c0) + Vector3d.Dot(r1, c1) + Vector3d.Dot(r2, c2);
            var omega = NewtonStep(r0, r1, r2, c0, c1, c2, trace, torque, out var solved)
                ? solved
                : torque / (Math.Abs(trace) + eps);
            if (!(omega.LengthSquared > Converged * Converged))
            {
                break;
            }

            q = (Quaternion4d.FromRotationVector(omega) * q).Normalized();
        }

        return q;
    }

    /// <summary>omega = (tr(B) 1 - B)^-1 t by cofactors, B = sum_i r_i a_i^T; false when the determinant is not positive.</summary>
    private static bool NewtonStep(
        Vector3d r0, Vector3d r1, Vector3d r2, Vector3d a0, Vector3d a1, Vector3d a2, double trace, Vector3d t, out Vector3d omega)
    {
        // M = tr(B) 1 - B with B_jk = sum_i r_i,j a_i,k.
        var m00 = trace - ((r0.X * a0.X) + (r1.X * a1.X) + (r2.X * a2.X));
        var m01 = -((r0.X * a0.Y) + (r1.X * a1.Y) + (r2.X * a2.Y));
        var m02 = -((r0.X * a0.Z) + (r1.X * a1.Z) + (r2.X * a2.Z));
        var m10 = -((r0.Y * a0.X) + (r1.Y * a1.X) + (r2.Y * a2.X));
        var m11 = trace - ((r0.Y * a0.Y) + (r1.Y * a1.Y) + (r2.Y * a2.Y));
        var m12 = -((r0.Y * a0.Z) + (r1.Y * a1.Z) + (r2.Y * a2.Z));
        var m20 = -((r0.Z * a0.X) + (r1.Z * a1.X) + (r2.Z * a2.X));
        var m21 = -((r0.Z * a0.Y) + (r1.Z * a1.Y) + (r2.Z * a2.Y));
        var m22 = trace - ((r0.Z * a0.Z) + (r1.Z * a1.Z) + (r2.Z * a2.Z));
        var c00 = (m11 * m22) - (m12 * m21);
        var c01 = (m02 * m21) - (m01 * m22);
        var c02 = (m01 * m12) - (m02 * m11);
        var det = (m00 * c00) + (m10 * c01) + (m20 * c02);
        if (!(det > 0.0) || double.IsInfinity(det))
        {
            omega = default;
            return false;
        }

        var c10 = (m12 * m20) - (m10 * m22);
        var c11 = (m00 * m22) - (m02 * m20);
        var c12 = (m02 * m10) - (m00 * m12);
        var c20 = (m10 * m21) - (m11 * m20);
        var c21 = (m01 * m20) - (m00 * m21);
        var c22 = (m00 * m11) - (m01 * m10);
        omega = new Vector3d(
            ((c00 * t.X) + (c01 * t.Y) + (c02 * t.Z)) / det,
            ((c10 * t.X) + (c11 * t.Y) + (c12 * t.Z)) / det,
            ((c20 * t.X) + (c21 * t.Y) + (c22 * t.Z)) / det);
        return true;
    }
}
