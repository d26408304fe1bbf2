using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Bodies;

/// <summary>
/// The winding number of a closed triangle mesh about a point: the solid angle its triangles subtend there, over 4 pi.
/// It is 1 inside a mesh whose triangles face outwards, -1 inside one that faces inwards and 0 outside, whatever the
/// point's position against the mesh's edges and vertices; a ray's crossing count is not, and a lattice aligned with a
/// box mesh puts its rays through the diagonals of the faces.
/// </summary>
/// <remarks>
/// A triangle's solid angle from the point p, with a, b, c its corners from p (Van Oosterom and Strackee, 1983):
/// tan(Omega / 2) = a . (b x c) / (|a| |b| |c| + (a . b) |c| + (b . c) |a| + (c . a) |b|), the angle taken with atan2 so
/// that it lies in (-2 pi, 2 pi]. The library's own atan2 gives the same bits on every runtime.
/// </remarks>
internal static class WindingNumber
{
    /// <summary>The winding number about <paramref name="point"/> of the triangles (corner indices, three each).</summary>
    public static double At(Vector3d point, Span<Vector3d> vertices, Span<int> triangles)
    {
        var sum = 0.0;
        for (var t = 0; t + 2 < triangles.Length; t += 3)
        {
            var a = vertices[triangles[t]] - point;
            var b = vertices[triangles[t + 1]] - point;
            var c = vertices[triangles[t + 2]] - point;
            double la = a.Length, lb = b.Length, lc = c.Length;
            var numerator = Vector3d.Dot(a, Vector3d.Cross(b, c));
            var denominator = (la * lb * lc) + (Vector3d.Dot(a, b) * lc) + (Vector3d.Dot(b, c) * la) + (Vector3d.Dot(c, a) * lb);
            sum += 2.0 * DeterministicTrig.Atan2(numerator, denominator);
        }

        return sum / (4.0 * Math.PI);
    }
}
