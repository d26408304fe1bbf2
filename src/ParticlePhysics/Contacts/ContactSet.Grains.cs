using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>
/// Grains: particles that are solid spheres with a spin of their own, for granular matter (sand, gravel, a pile of
/// balls). Their contacts act at the contact point, so that friction can roll a grain as well as stop it, and a rolling
/// resistance holds piles at an angle; under the position-based integrator only (a force-based step leaves spins alone).
/// </summary>
/// <remarks>
/// <para>
/// A grain of radius r and inverse mass w has the inertia I = 2/5 m r^2 of a solid sphere, so r^2 / I = 5/2 w. At a
/// contact of normal n (from b to a), a's contact point is at -r_a n and b's at r_b n: the contact points' relative
/// velocity is v_a - v_b - (r_a omega_a + r_b omega_b) x n, and a tangential impulse P (on a, -P on b) changes it by
/// K P with K = w_a + w_b + r_a^2 / I_a + r_b^2 / I_b (the spin terms only for grains), while omega_a changes by
/// -(r_a / I_a) n x P and omega_b by -(r_b / I_b) n x P.
/// </para>
/// <para>
/// Static friction on an obstacle, in the projection: a grain held still (its move over the substep undone in the
/// tangent plane by moves alone, its spin across the normal stopped) when that takes a friction within mu_s N and a
/// rolling torque within mu_r r N, so a grain on a slope with tan(theta) &lt;= mu_r stays put;
/// else its contact point's move u = dx - h V - h r omega x n is undone when |u_t| &lt; mu_s d (d the normal correction,
/// Macklin et al. 2014's rule) by P = -u_t / K shared between moves and spins (a spin's share as omega += its change /
/// h), so a grain that rolls keeps its contact point still and one that would slide is held. Between two particles
/// friction acts in the velocity pass only, as for plain particles: in one sweep, a stick in the projection undoes
/// the tangential part of the other contacts' normal pushes and spreads a stack outward (the pyramid test).
/// Dynamic friction, in the velocity pass: P = -v_t / K with |P| &lt;= mu_k J_n, J_n = (d / h) / (w_a + w_b) the
/// normal impulse of the projection. Rolling resistance, after it: the relative spin across the normal is taken down by
/// an angular impulse L = -omega_r / (1/I_a + 1/I_b) with |L| &lt;= mu_r R J_n, R = r_a r_b / (r_a + r_b) (r_a on an
/// obstacle): a torque up to mu_r R times the normal force, the constant-torque model of Ai et al. (2011). So a grain
/// sliding onto flat ground ends rolling at 5/7 of its speed, rolls down a slope at 5/7 g sin(theta), and a rolling
/// one stops after v^2 / (2 (5/7) mu_r g) (tests).
/// </para>
/// </remarks>
public sealed partial class ContactSet
{
    private double[] _rolling = Array.Empty<double>(); // NaN: not a grain
    private double[] _staticFriction = Array.Empty<double>();
    private Vector3d[] _spin = Array.Empty<Vector3d>();
    private Vector3d[] _savedSpin = Array.Empty<Vector3d>();
    private bool _anyGrains;

    /// <summary>
    /// Makes the particles <paramref name="first"/> to <paramref name="first"/> + <paramref name="count"/> - 1 grains:
    /// solid spheres of their radius with a spin, a static friction coefficient <paramref name="staticFriction"/> on
    /// obstacles (met with the obstacle's friction by their mean) and a rolling friction coefficient
    /// <paramref name="rollingFriction"/> (the resisting torque over the normal force times the contact's radius; a
    /// grain's alone where the other side is not one, the mean where both are). Their dynamic friction is their
    /// material's (<see cref="SetParticleMaterial"/>), or the set's. Spins start at rest. Indices past the world's
    /// particles apply to particles added there later.
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">A range out of bounds, or a coefficient not a finite number &gt;= 0.</exception>
    public void SetGranular(int first, int count, double staticFriction, double rollingFriction)
    {
        CheckParticleRange(first, count);
        Guard.NonNegativeFinite(staticFriction, nameof(staticFriction));
        Guard.NonNegativeFinite(rollingFriction, nameof(rollingFriction));
        if (_rolling.Length < first + count)
        {
            var length = Math.Max(first + count, 2 * _rolling.Length);
            var old = _rolling.Length;
            Array.Resize(ref _rolling, length);
            Array.Resize(ref _staticFriction, length);
            Array.Resize(ref _spin, length);
            Array.Resize(ref _savedSpin, length);
            _rolling.AsSpan(old).Fill(double.NaN);
        }

        _rolling.AsSpan(first, count).Fill(rollingFriction);
        _staticFriction.AsSpan(first, count).Fill(staticFriction);
        _spin.AsSpan(first, count).Clear();
        _anyGrains = true;
        _revision++;
    }

    /// <summary>Whether particle <paramref name="particle"/> is a grain (<see cref="SetGranular"/>).</summary>
    public bool IsGrain(int particle) => (uint)particle < (uint)_rolling.Length && !double.IsNaN(_rolling[particle]);

    /// <summary>The spin (angular velocity, rad/s) of grain <paramref name="particle"/>; zero for a particle that is not one.</summary>
    public Vector3d GetSpin(int particle)
    {
        if (particle < 0)
        {
            throw new ArgumentOutOfRangeException(nameof(particle), particle, $"particle must be an index >= 0; got {particle}.");
        }

        return IsGrain(particle) ? _spin[particle] : Vector3d.Zero;
    }

    /// <summary>Sets the spin of grain <paramref name="particle"/>, rad/s.</summary>
    /// <exception cref="ArgumentException">The particle is not a grain, or the spin is not finite.</exception>
    public void SetSpin(int particle, Vector3d spin)
    {
        if (!IsGrain(particle))
        {
            throw new ArgumentException($"Particle {particle} is not a grain: give it SetGranular first.", nameof(particle));
        }

        Guard.Finite(spin, nameof(spin));
        _spin[particle] = spin;
    }

    private void SaveSpins()
    {
        if (_anyGrains)
        {
            Array.Copy(_spin, _savedSpin, _spin.Length);
        }
    }

    private void RestoreSpins()
    {
        if (_anyGrains)
        {
            Array.Copy(_savedSpin, _spin, _spin.Length);
        }
    }

    // r^2 / I of a grain (5/2 w), 0 for a particle without spin.
    private double SpinShare(int i, double w, double r) => w > 0.0 && r > 0.0 && IsGrain(i) ? 2.5 * w : 0.0;

    private Vector3d SpinOf(int i) => IsGrain(i) ? _spin[i] : Vector3d.Zero;

    private double PairRolling(int a, int b) =>
        IsGrain(a) && IsGrain(b) ? 0.5 * (_rolling[a] + _rolling[b]) : IsGrain(a) ? _rolling[a] : IsGrain(b) ? _rolling[b] : 0.0;

    /// <summary>Static friction of a grain on an obstacle: returns its position with the contact point's tangential move undone when within mu_s d.</summary>
    private Vector3d StickGrain(int i, Vector3d position, Vector3d start, Obstacle obstacle, Vector3d n, double depth, double w, double r, double h)
    {
        var k = SpinShare(i, w, r);
        var muS = 0.5 * (_staticFriction[i] + obstacle.Friction);
        var move = position - start - (h * obstacle.Velocity);
        var tangential = move - (Vector3d.Dot(move, n) * n);
        if (HoldsStill(tangential, w, muS * depth, _rolling[i] * r * depth, h, k, r, _spin[i], n))
        {
            StopRolling(i, k, n);
            return position - tangential;
        }

        // The contact point's move: the centre's less the spin's, h r omega x n.
        var u = move - (h * r * Vector3d.Cross(_spin[i], n));
        var ut = u - (Vector3d.Dot(u, n) * n);

        if (!(ut.Length < muS * depth) || w == 0.0)
        {
            return position;
        }

        var p = -ut / (w + k);
        if (k > 0.0)
        {
            _spin[i] -= (k / r) * Vector3d.Cross(n, p) / h;
        }

        return position + (w * p);
    }

    /// <summary>
    /// Static rolling, in the projection: whether a contact can hold one side still, its tangential move u_t (of the
    /// centres, relative) undone by moves alone and its spin across the normal stopped, within the contact's limits
    /// (given times h w, as mu d): a friction |u_t| &lt;= mu_s d, the friction's torque on the side r |u_t| and the
    /// angular impulse that stops it (I / h) |omega_t| h w each within mu_r R d. The friction's torque on each grain is
    /// then taken by the rolling resistance there, as the grain's other contacts would share it in a pile at rest; it
    /// is exact on an obstacle (a grain on a slope holds while tan(theta) &lt;= mu_r). Past a limit, the contact point's
    /// stick and the velocity pass's resistance let it roll.
    /// </summary>
    private static bool HoldsStill(Vector3d ut, double w, double frictionLimit, double rollingLimit, double h, double k, double r, Vector3d spin, Vector3d n)
    {
        if (!(w > 0.0) || !(rollingLimit > 0.0))
        {
            return false;
        }

        if (!(ut.Length <= frictionLimit))
        {
            return false;
        }

        if (!(k > 0.0))
        {
            return true;
        }

        var across = spin - (Vector3d.Dot(spin, n) * n);
        return r * ut.Length <= rollingLimit && (r * r / k) * across.Length * h * w <= rollingLimit;
    }

    // A held grain's spin across the contact's normal stops; its spin about the normal (twist) is left.
    private void StopRolling(int i, double k, Vector3d n)
    {
        if (k > 0.0)
        {
            _spin[i] = Vector3d.Dot(_spin[i], n) * n;
        }
    }

    /// <summary>
    /// The velocity pass of a contact with a grain: dynamic friction at the contact point, then rolling resistance.
    /// Returns the tangential impulse P over the masses' scale (a's velocity changes by w_a P, b's by -w_b P).
    /// </summary>
    private Vector3d SolveGrainFriction(int a, int b, Vector3d relative, Vector3d n, double mu, double jn, double wa, double wb, double ra, double rb, double muRolling)
    {
        double ka = SpinShare(a, wa, ra), kb = b >= 0 ? SpinShare(b, wb, rb) : 0.0;
        var spinB = b >= 0 ? SpinOf(b) : Vector3d.Zero;
        var contact = relative - Vector3d.Cross((ra * SpinOf(a)) + (rb * spinB), n);
        var tangent = contact - (Vector3d.Dot(contact, n) * n);
        var p = -tangent / (wa + wb + ka + kb);
        var limit = mu * jn;
        if (p.Length > limit)
        {
            p *= limit / p.Length;
        }

        var turn = Vector3d.Cross(n, p);
        if (ka > 0.0)
        {
            _spin[a] -= (ka / ra) * turn;
        }

        if (kb > 0.0)
        {
            _spin[b] -= (kb / rb) * turn;
        }

        // Rolling resistance: 1 / I = (r^2 / I) / r^2.
        double ia = ka > 0.0 ? ka / (ra * ra) : 0.0, ib = kb > 0.0 ? kb / (rb * rb) : 0.0;
        if (ia + ib > 0.0 && muRolling > 0.0)
        {
            var relativeSpin = SpinOf(a) - spinB;
            var rolling = relativeSpin - (Vector3d.Dot(relativeSpin, n) * n);
            var angular = -rolling / (ia + ib);
            var radius = b >= 0 && rb > 0.0 ? ra * rb / (ra + rb) : ra;
            var most = muRolling * radius * jn;
            if (angular.Length > most)
            {
                angular *= most / angular.Length;
            }

            _spin[a] += ia * angular;
            if (b >= 0 && ib > 0.0)
            {
                _spin[b] -= ib * angular;
            }
        }

        return p;
    }
}
