using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Sliding friction over an interval of resting contact, exactly for constant forces: the correction that Coulomb
/// friction of deceleration f = mu N / m makes to the motion an integrator computed without it, along one tangent
/// direction.
/// </summary>
/// <remarks>
/// <para>
/// Along the unit tangent w (the sliding direction at the start of the interval, or the way the applied force pushes
/// when the particle starts at rest), the particle starts at speed w0 &gt;= 0 under the applied tangential acceleration
/// a. While it slides forward, w' = a - f. If it never stops within the interval tau, friction takes f tau off the
/// speed and f tau^2 / 2 off the distance. If it stops at t = w0 / (f - a) &lt; tau, it then sticks when |a| &lt;= f
/// (static friction holds it: the tangential force is cancelled) or slides back with w' = a + f.
/// </para>
/// <para>
/// What the integrator did without friction, for a constant a: every integrator of the library changes the velocity
/// exactly, by a tau, but the distance by w0 tau + c a tau^2, with c = 1/2 for RK4, velocity Verlet and RK45 (exact),
/// c = 1 for semi-implicit and implicit Euler (x += tau v_new) and c = 0 for explicit Euler (x += tau v_old). So the
/// speed's correction is the frictional speed less w0 + a tau for all of them, and the distance's is taken against the
/// distance the integrator actually moved, <c>moved</c>. While the particle slides the whole interval, friction is one
/// more constant acceleration whose exact part, -f tau^2 / 2, adds to the integrator's own motion (superposition: the
/// integrator keeps its order). Once it stops within the interval, or never starts, where it ends is fixed by w0, a
/// and f alone, and replaces what the integrator moved: a particle held by static friction ends exactly where it came
/// to rest under every integrator, where taking a tau^2 / 2 off would leave it (c - 1/2) a tau^2 away each step. The
/// corrections never take off more than the free motion adds, so friction stops a particle and never reverses it.
/// </para>
/// </remarks>
internal static class CoulombSlide
{
    /// <summary>The change of speed and of distance along the tangent that friction makes over the interval.</summary>
    /// <param name="w0">The speed along the tangent at the start of the interval, &gt;= 0.</param>
    /// <param name="a">The applied tangential acceleration along it.</param>
    /// <param name="f">The friction deceleration mu N / m, &gt;= 0.</param>
    /// <param name="tau">The interval, in seconds, &gt; 0.</param>
    /// <param name="moved">The distance along the tangent that the integrator moved the particle over the interval.</param>
    /// <param name="dw">Receives the change of speed.</param>
    /// <param name="dx">Receives the change of distance.</param>
    public static void Correction(double w0, double a, double f, double tau, double moved, out double dw, out double dx)
    {
        var sliding = a - f;
        if (w0 <= 0.0 && a <= f)
        {
            // At rest, and the applied force does not overcome static friction: it stays where it came to rest.
            dw = -a * tau;
            dx = -moved;
            return;
        }

        var stop = sliding < 0.0 ? w0 / -sliding : double.PositiveInfinity;
        if (!(stop < tau))
        {
            dw = -f * tau;
            dx = -0.5 * f * tau * tau;
            return;
        }

        var freeSpeed = w0 + (a * tau);
        var distance = (w0 * stop) + (0.5 * sliding * stop * stop);
        var speed = 0.0;
        if (Math.Abs(a) > f)
        {
            // The applied force pushes it back harder than friction holds: it slides back for the rest.
            var back = a + f;
            var rest = tau - stop;
            speed = back * rest;
            distance += 0.5 * back * rest * rest;
        }

        dw = speed - freeSpeed;
        dx = distance - moved;
    }
}
