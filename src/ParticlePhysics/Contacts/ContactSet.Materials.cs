using System;

namespace ParticlePhysics.Contacts;

// Per-particle friction and restitution (a rigid body's, a granular material's), combined with the other side's by their mean.
public sealed partial class ContactSet
{
    private double[] _ownFriction = Array.Empty<double>();    // NaN: the particle has none of its own
    private double[] _ownRestitution = Array.Empty<double>();

    /// <summary>
    /// Gives the particles <paramref name="first"/> to <paramref name="first"/> + <paramref name="count"/> - 1 (a rigid
    /// body, a granular material) a friction coefficient and a restitution of their own. A contact where both sides
    /// carry one uses the mean of the two, as Unity does by default: with an obstacle, the mean of the particle's and the
    /// obstacle's; between particles, the mean of theirs, a particle without its own counting as
    /// <see cref="ParticleFriction"/> and <see cref="ParticleRestitution"/>. Particles never set use the obstacle's
    /// values, and the set's between particles, unchanged. <see cref="double.NaN"/> for either value gives the particles
    /// none of their own for that one (a body with a friction of its own but not a restitution). Indices past the world's
    /// particles apply to particles added there later.
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">
    /// <paramref name="first"/> or <paramref name="count"/> out of range, <paramref name="friction"/> neither NaN nor a
    /// finite number &gt;= 0, or <paramref name="restitution"/> neither NaN nor in [0, 1].
    /// </exception>
    public void SetParticleMaterial(int first, int count, double friction, double restitution)
    {
        CheckParticleRange(first, count);
        if (!double.IsNaN(friction))
        {
            Guard.NonNegativeFinite(friction, nameof(friction));
        }

        if (!double.IsNaN(restitution))
        {
            CheckRestitution(restitution, nameof(restitution));
        }

        if (_ownFriction.Length < first + count)
        {
            var length = Math.Max(first + count, 2 * _ownFriction.Length);
            var old = _ownFriction.Length;
            Array.Resize(ref _ownFriction, length);
            Array.Resize(ref _ownRestitution, length);
            _ownFriction.AsSpan(old).Fill(double.NaN);
            _ownRestitution.AsSpan(old).Fill(double.NaN);
        }

        _ownFriction.AsSpan(first, count).Fill(friction);
        _ownRestitution.AsSpan(first, count).Fill(restitution);
        _revision++;
    }

    /// <summary>
    /// Particle <paramref name="particle"/>'s own friction and restitution (NaN for one it has none of), or null when it
    /// has neither (<see cref="SetParticleMaterial"/>).
    /// </summary>
    public (double Friction, double Restitution)? GetParticleMaterial(int particle)
    {
        if (particle < 0)
        {
            throw new ArgumentOutOfRangeException(nameof(particle), particle, $"particle must be an index >= 0; got {particle}.");
        }

        return particle < _ownFriction.Length && !(double.IsNaN(_ownFriction[particle]) && double.IsNaN(_ownRestitution[particle]))
            ? (_ownFriction[particle], _ownRestitution[particle])
            : null;
    }

    private double FrictionWith(Obstacle obstacle, int particle) =>
        (uint)particle < (uint)_ownFriction.Length && !double.IsNaN(_ownFriction[particle]) ? 0.5 * (_ownFriction[particle] + obstacle.Friction) : obstacle.Friction;

    private double RestitutionWith(Obstacle obstacle, int particle) =>
        (uint)particle < (uint)_ownRestitution.Length && !double.IsNaN(_ownRestitution[particle]) ? 0.5 * (_ownRestitution[particle] + obstacle.Restitution) : obstacle.Restitution;

    // (f + f) / 2 is f exactly, so pairs of particles without their own keep the set's values to the bit.
    private double PairFriction(int a, int b) => _ownFriction.Length == 0 ? _particleFriction : 0.5 * (OwnOr(_ownFriction, a, _particleFriction) + OwnOr(_ownFriction, b, _particleFriction));

    private double PairRestitution(int a, int b) => _ownRestitution.Length == 0 ? _particleRestitution : 0.5 * (OwnOr(_ownRestitution, a, _particleRestitution) + OwnOr(_ownRestitution, b, _particleRestitution));

    private static double OwnOr(double[] own, int particle, double otherwise) =>
        (uint)particle < (uint)own.Length && !double.IsNaN(own[particle]) ? own[particle] : otherwise;
}
