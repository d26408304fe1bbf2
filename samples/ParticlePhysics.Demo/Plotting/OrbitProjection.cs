using System;

namespace ParticlePhysics.Demo.Plotting;

/// <summary>
/// A perspective view from a camera that orbits a target (the replay page's camera): yaw about the vertical axis y,
/// pitch above the horizon, a distance, a 40 degree field of view. <see cref="Project"/> gives the point on a unit
/// image plane (x right, y up) and its depth along the view, for a painter's sort.
/// </summary>
internal sealed class OrbitProjection
{
    private readonly Vector3d _eye;
    private readonly Vector3d _right;
    private readonly Vector3d _up;
    private readonly Vector3d _forward;
    private readonly double _focal;

    /// <param name="target">The point looked at.</param>
    /// <param name="distance">From the eye to the target, in the scene's units.</param>
    /// <param name="yaw">About +y, in radians; 0 looks along -z.</param>
    /// <param name="pitch">Above the horizon, in radians.</param>
    public OrbitProjection(Vector3d target, double distance, double yaw, double pitch)
    {
        double cp = Math.Cos(pitch), sp = Math.Sin(pitch), cy = Math.Cos(yaw), sy = Math.Sin(yaw);
        _eye = target + (distance * new Vector3d(cp * sy, sp, cp * cy));
        _forward = new Vector3d(-cp * sy, -sp, -cp * cy);
        var right = new Vector3d(-_forward.Z, 0, _forward.X);
        _right = right / right.Length;
        _up = Vector3d.Cross(_right, _forward);
        _focal = 1 / Math.Tan(FieldOfView / 2);
    }

    /// <summary>The vertical field of view, in radians.</summary>
    public static double FieldOfView => 40 * Math.PI / 180;

    /// <summary>Where the camera is.</summary>
    public Vector3d Eye => _eye;

    /// <summary>The camera's direction of view (unit).</summary>
    public Vector3d Forward => _forward;

    /// <summary>The camera's up direction on the image (unit).</summary>
    public Vector3d Up => _up;

    /// <summary>The camera's right direction on the image (unit).</summary>
    public Vector3d Right => _right;

    /// <summary>A camera that sees the whole box from <paramref name="low"/> to <paramref name="high"/> from the given angles.</summary>
    public static OrbitProjection Fitting(Vector3d low, Vector3d high, double yaw, double pitch)
    {
        var radius = Math.Max(0.5 * (high - low).Length, 1e-9);
        return new OrbitProjection(0.5 * (low + high), 1.05 * radius / Math.Sin(FieldOfView / 2), yaw, pitch);
    }

    /// <summary>The image of <paramref name="p"/>: (x, y) on the image plane at unit focal distance scaled by the field of view, and the depth.</summary>
    public (double X, double Y, double Depth) Project(Vector3d p)
    {
        var q = p - _eye;
        var depth = Vector3d.Dot(q, _forward);
        var d = Math.Max(depth, 1e-12);
        return (_focal * Vector3d.Dot(q, _right) / d, _focal * Vector3d.Dot(q, _up) / d, depth);
    }
}
