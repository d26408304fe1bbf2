using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Sliding friction over an interval of resting contact, exactly for constant forces: the correction that Coulomb
/// friction of deceleration f = mu N / m makes to a free motion along one tangent direction.
/// </summary>
/// <remarks>
/// Along the unit tangent w (the sliding direction at the start of the interval, or the way the applied force pushes
/// when the particle starts at rest), the particle starts at speed w0 &gt;= 0 under the applied tangential acceleration
/// a. While it slides forward, w' = a - f. If it never stops within the interval tau, friction takes f tau off the
/// speed and f tau^2 / 2 off the distance. If it stops at t = w0 / (f - a) &lt; tau, it then sticks when |a| &lt;= f
/// (static friction holds it: the tangential force is cancelled) or slides back with w' = a + f. The corrections are
/// the frictional motion less the free one (w0 + a tau, w0 tau + a tau^2 / 2): they take off at most what the free
/// motion adds, so friction stops a particle and never reverses it.
/// </remarks>
internal static class CoulombSlide
{
    /// <summary>The change of speed and of distance along the tangent that friction makes over the interval.</summary>
    /// <param name="w0">The speed along the tangent at the start of the interval, &gt;= 0.</param>
    /// <param name="a">The applied tangential acceleration along it.</param>
    /// <param name="f">The friction deceleration mu N / m, &gt;= 0.</param>
    /// <param name="tau">The interval, in seconds, &gt; 0.</param>
    /// <param name="dw">Receives the change of speed.</param>
    /// <param name="dx">Receives the change of distance.</param>
    public static void Correction(double w0, double a, double f, double tau, out double dw, out double dx)
    {
        var sliding = a - f;
        if (w0 <= 0.0 && a <= f)
        {
            // At rest, and the applied force does not overcome static friction: it stays.
            dw = -a * tau;
            dx = -0.5 * a * tau * tau;
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
        var freeDistance = (w0 * tau) + (0.5 * a * tau * tau);
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
        dx = distance - freeDistance;
    }
}
