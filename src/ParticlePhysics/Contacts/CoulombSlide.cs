using System;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Sliding friction over an interval of resting contact, exactly for constant forces: the correction that Coulomb
/// friction of deceleration f = mu N / m makes to the tangential motion an integrator computed without it.
/// </summary>
/// <remarks>
/// <para>
/// The particle starts the interval tau with tangential velocity w0 and ends it, as the integrator left it, with w1;
/// the applied tangential acceleration is a = (w1 - w0) / tau. Friction acts against the velocity: w' = a - f w / |w|.
/// On a straight line (w0 and a parallel, or either zero) that is solved exactly. Along u, w0's direction,
/// w' = a . u - f while the particle slides forward; if that speed reaches 0 within tau, at t_s = |w0| / (f - a . u),
/// the particle is at rest from there on (from the start, if w0 = 0), and what it does next depends on the whole applied
/// force, not on the direction it came from: it sticks when |a| &lt;= f (static friction cancels the tangential force),
/// or it slides along a with acceleration |a| - f. If it slides the whole interval, friction takes f tau off the speed
/// of the free end velocity w1 along w1's own direction (the friction direction taken at the end, as an implicit step
/// takes it: a velocity turning towards a under friction never swings past it), and the position follows the mean of
/// the start and end velocities. Off a straight line these are approximations of the curving slide, second order in
/// tau. (Friction along u for the whole interval swung a slow slide's velocity across a from side to side: a rounding
/// residue of 1e-17 m/s grew tenfold a step; and deciding a stop along u alone let the part of a across u move a
/// particle at rest.)
/// </para>
/// <para>
/// What the integrator did without friction, for a constant a: every integrator of the library changes the velocity
/// exactly, by a tau, but the position by w0 tau + c a tau^2, with c = 1/2 for RK4, velocity Verlet and RK45 (exact),
/// c = 1 for semi-implicit and implicit Euler (x += tau v_new) and c = 0 for explicit Euler (x += tau v_old). So the
/// velocity's correction is the frictional velocity less w1 for all of them, and the position's replaces the tangential
/// displacement the integrator made (<c>moved</c>) by the frictional one. The tangential motion of a resting particle
/// is then exact for constant forces under every integrator: a slide stops after v0^2 / (2 mu g), a particle held by
/// static friction ends exactly where it came to rest, and friction never reverses a slide. (Adding friction's
/// -f tau^2 / 2 to the integrator's displacement is exact for c = 1/2 only: a held particle crept by (c - 1/2) a tau^2
/// a step, and under explicit Euler a slide just begun went back up the slope.)
/// </para>
/// </remarks>
internal static class CoulombSlide
{
    /// <summary>The change of tangential velocity and of position that friction makes over the interval.</summary>
    /// <param name="w0">The tangential velocity at the start of the interval.</param>
    /// <param name="w1">The tangential velocity the integrator left at its end.</param>
    /// <param name="f">The friction deceleration mu N / m, &gt;= 0.</param>
    /// <param name="tau">The interval, in seconds, &gt; 0.</param>
    /// <param name="moved">The tangential displacement the integrator made over the interval.</param>
    /// <param name="dw">Receives the change of velocity.</param>
    /// <param name="dx">Receives the change of position.</param>
    public static void Correction(Vector3d w0, Vector3d w1, double f, double tau, Vector3d moved, out Vector3d dw, out Vector3d dx)
    {
        var speed = w0.Length;
        var stop = 0.0;
        var atStop = Vector3d.Zero; // the displacement from the start of the interval to the stop
        if (speed > 0.0)
        {
            var u = w0 / speed;
            var along = (Vector3d.Dot(w1, u) - speed) / tau;
            var sliding = along - f;
            stop = sliding < 0.0 ? speed / -sliding : double.PositiveInfinity;
            if (!(stop < tau))
            {
                // It slides throughout: friction against the direction of the velocity at the end (the free end
                // velocity's, as an implicit step takes it), which on a straight line is the exact -f tau; the position
                // from the mean of the two velocities, exact on a straight line under a constant force.
                var free = w1.Length;
                var slid = ((free - (f * tau)) / free) * w1;
                dw = slid - w1;
                dx = ((0.5 * tau) * (w0 + slid)) - moved;
                return;
            }

            // Along u it decelerates to rest; across u the applied force acted alone until then.
            var across = ((w1 - w0) / tau) - (along * u);
            atStop = (((speed * stop) + (0.5 * sliding * stop * stop)) * u) + ((0.5 * stop * stop) * across);
        }
        else if (w1 == Vector3d.Zero)
        {
            dw = Vector3d.Zero; // at rest, and nothing pushes it
            dx = Vector3d.Zero;
            return;
        }

        // At rest from the stop on: it sticks while the applied force is within the friction cone, else slides along it.
        var a = (w1 - w0) / tau;
        var push = a.Length;
        var end = atStop;
        var velocity = Vector3d.Zero;
        if (push > f)
        {
            var rest = tau - stop;
            var direction = a / push;
            velocity = ((push - f) * rest) * direction;
            end += (0.5 * (push - f) * rest * rest) * direction;
        }

        dw = velocity - w1;
        dx = end - moved;
    }
}
