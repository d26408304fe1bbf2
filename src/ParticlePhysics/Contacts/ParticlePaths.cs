using System;
using System.Runtime.CompilerServices;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The path of every particle within one step, as the contact search sees it: the cubic Hermite curve through the
/// integrator's start (x0, v0) and end (x1, v1), corrected by each impulse the step has applied so far.
/// </summary>
/// <remarks>
/// <para>
/// p(s) = x0 + v0 s + c2 s^2 + c3 s^3 with c2 = (3 (x1 - x0) / T - 2 v0 - v1) / T and c3 = (2 (x0 - x1) / T + v0 + v1) / T^2
/// matches both ends' positions and velocities. A cubic reproduces any quadratic, so for a particle under constant
/// forces (gravity) whose step RK4 or velocity Verlet integrates exactly, the curve is the particle's parabola and
/// impact times found on it are exact.
/// </para>
/// <para>
/// An impulse dv at time s changes the velocity from s on; under forces that do not depend on the state, the motion
/// after s is the old one plus dv (t - s) (superposition), so the curve is re-expanded (a Taylor shift) about s and dv
/// added to its slope: p(s + u) = p(s) + (p'(s) + dv) u + (c2 + 3 c3 (s - o)) u^2 + c3 u^3, exact for constant forces
/// and first order in the step otherwise. Each particle keeps 12 coefficients and the time o they are expanded about.
/// </para>
/// <para>
/// Each path also has a version, bumped by a bounce (<see cref="Bounce"/>): an impact found on an older version of a
/// path is stale (<see cref="ImpactQueue"/> skips it). A resting impulse changes the path by less than the resting
/// speed and keeps its version, so what was queued before it stands.
/// </para>
/// </remarks>
internal sealed class ParticlePaths
{
    private double[] _origin = Array.Empty<double>();
    private double[] _coefficients = Array.Empty<double>();
    private int[] _version = Array.Empty<int>();

    /// <summary>Makes room for <paramref name="count"/> particles (allocates only when the count grows).</summary>
    public void EnsureCapacity(int count)
    {
        if (_origin.Length < count)
        {
            _origin = new double[count];
            _coefficients = new double[12 * count];
            _version = new int[count];
        }
    }

    /// <summary>Particle <paramref name="i"/>'s curve through (x0, v0) at s = 0 and (x1, v1) at s = T.</summary>
    public void SetHermite(int i, Vector3d x0, Vector3d v0, Vector3d x1, Vector3d v1, double duration)
    {
        var chord = (x1 - x0) / duration;
        var c2 = ((3.0 * chord) - (2.0 * v0) - v1) / duration;
        var c3 = (v0 + v1 - (2.0 * chord)) / (duration * duration);
        _origin[i] = 0.0;
        _version[i] = 0;
        Write(i, x0, v0, c2, c3);
    }

    /// <summary>The version of particle <paramref name="i"/>'s path: 0 when set, one more after each bounce.</summary>
    public int Version(int i) => _version[i];

    /// <summary>Particle <paramref name="i"/> bounced: impacts found on its path before are stale.</summary>
    public void Bounce(int i) => _version[i]++;

    /// <summary>The position and velocity of particle <paramref name="i"/> at time <paramref name="s"/> into the step.</summary>
    public void Evaluate(int i, double s, out Vector3d position, out Vector3d velocity)
    {
        Evaluate(i, s, out var px, out var py, out var pz, out var vx, out var vy, out var vz);
        position = new Vector3d(px, py, pz);
        velocity = new Vector3d(vx, vy, vz);
    }

    /// <summary>The same, component by component: the contact search's inner loop.</summary>
    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    public void Evaluate(
        int i, double s, out double px, out double py, out double pz, out double vx, out double vy, out double vz)
    {
        var u = s - _origin[i];
        var c = _coefficients.AsSpan(12 * i, 12);
        px = c[0] + (u * (c[3] + (u * (c[6] + (u * c[9])))));
        py = c[1] + (u * (c[4] + (u * (c[7] + (u * c[10])))));
        pz = c[2] + (u * (c[5] + (u * (c[8] + (u * c[11])))));
        vx = c[3] + (u * ((2.0 * c[6]) + (3.0 * u * c[9])));
        vy = c[4] + (u * ((2.0 * c[7]) + (3.0 * u * c[10])));
        vz = c[5] + (u * ((2.0 * c[8]) + (3.0 * u * c[11])));
    }

    /// <summary>
    /// A bound on |p''| over [<paramref name="from"/>, <paramref name="to"/>]: p'' is linear in s, so its norm, a convex
    /// function, is largest at an end.
    /// </summary>
    public double AccelerationBound(int i, double from, double to)
    {
        var c = _coefficients.AsSpan(12 * i, 12);
        var o = _origin[i];
        double u0 = 6.0 * (from - o), u1 = 6.0 * (to - o);
        double ax = (2.0 * c[6]) + (u0 * c[9]), ay = (2.0 * c[7]) + (u0 * c[10]), az = (2.0 * c[8]) + (u0 * c[11]);
        double bx = (2.0 * c[6]) + (u1 * c[9]), by = (2.0 * c[7]) + (u1 * c[10]), bz = (2.0 * c[8]) + (u1 * c[11]);
        return Math.Sqrt(Math.Max((ax * ax) + (ay * ay) + (az * az), (bx * bx) + (by * by) + (bz * bz)));
    }

    /// <summary>
    /// A bound on |p_i'' - p_j''| over [<paramref name="from"/>, <paramref name="to"/>], the bend of the path of one
    /// particle seen from the other: two particles falling side by side have none.
    /// </summary>
    public double RelativeAccelerationBound(int i, int j, double from, double to)
    {
        Acceleration(i, from, out var aix, out var aiy, out var aiz);
        Acceleration(j, from, out var ajx, out var ajy, out var ajz);
        Acceleration(i, to, out var bix, out var biy, out var biz);
        Acceleration(j, to, out var bjx, out var bjy, out var bjz);
        double ax = aix - ajx, ay = aiy - ajy, az = aiz - ajz, bx = bix - bjx, by = biy - bjy, bz = biz - bjz;
        return Math.Sqrt(Math.Max((ax * ax) + (ay * ay) + (az * az), (bx * bx) + (by * by) + (bz * bz)));
    }

    /// <summary>Adds the impulse <paramref name="dv"/> at time <paramref name="s"/>: the curve is re-expanded about s.</summary>
    public void AddVelocity(int i, double s, Vector3d dv)
    {
        var u = s - _origin[i];
        Read(i, out var b0, out var b1, out var b2, out var b3);
        var position = b0 + (u * (b1 + (u * (b2 + (u * b3)))));
        var velocity = b1 + (u * ((2.0 * b2) + (3.0 * u * b3)));
        _origin[i] = s;
        Write(i, position, velocity + dv, b2 + (3.0 * u * b3), b3);
    }

    private void Acceleration(int i, double s, out double ax, out double ay, out double az)
    {
        var c = _coefficients.AsSpan(12 * i, 12);
        var u = 6.0 * (s - _origin[i]);
        ax = (2.0 * c[6]) + (u * c[9]);
        ay = (2.0 * c[7]) + (u * c[10]);
        az = (2.0 * c[8]) + (u * c[11]);
    }

    private void Read(int i, out Vector3d b0, out Vector3d b1, out Vector3d b2, out Vector3d b3)
    {
        var c = _coefficients;
        var o = 12 * i;
        b0 = new Vector3d(c[o], c[o + 1], c[o + 2]);
        b1 = new Vector3d(c[o + 3], c[o + 4], c[o + 5]);
        b2 = new Vector3d(c[o + 6], c[o + 7], c[o + 8]);
        b3 = new Vector3d(c[o + 9], c[o + 10], c[o + 11]);
    }

    private void Write(int i, Vector3d b0, Vector3d b1, Vector3d b2, Vector3d b3)
    {
        var c = _coefficients;
        var o = 12 * i;
        c[o] = b0.X;
        c[o + 1] = b0.Y;
        c[o + 2] = b0.Z;
        c[o + 3] = b1.X;
        c[o + 4] = b1.Y;
        c[o + 5] = b1.Z;
        c[o + 6] = b2.X;
        c[o + 7] = b2.Y;
        c[o + 8] = b2.Z;
        c[o + 9] = b3.X;
        c[o + 10] = b3.Y;
        c[o + 11] = b3.Z;
    }
}
