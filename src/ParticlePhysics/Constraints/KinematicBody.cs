using System;
using System.Collections.Generic;

namespace ParticlePhysics.Constraints;

/// <summary>
/// A moving body the host drives (a hand, a character's shoulder, a rotating platform), with particles attached at
/// fixed points of it: a pose (position and rotation) that the host updates each frame, and attached particles that
/// follow it as kinematic particles (pinned, with the velocity of their point's path), so that springs, dampers and
/// drag see the body's motion and a detached particle flies on with it. (Not named Transform, which would clash with
/// UnityEngine.Transform.)
/// </summary>
/// <remarks>
/// Attaching pins the particle and records its offset in the body's frame, r = R^-1 (x - p). Each
/// <see cref="MoveTo"/> gives the body its pose at the end of the next <c>duration</c> seconds, and each attached
/// particle the velocity (p' + R' r - x) / duration, so that it reaches its point exactly then (the chord of its path
/// over the frame; the world moves pinned particles at their velocity under every integrator). Call it once per frame,
/// before stepping that frame's time.
/// </remarks>
public sealed class KinematicBody
{
    private readonly ParticleWorld _world;
    private readonly List<int> _particles = new();
    private readonly List<Vector3d> _offsets = new();

    /// <summary>A body at <paramref name="position"/> with orientation <paramref name="orientation"/>, holding no particle yet.</summary>
    public KinematicBody(ParticleWorld world, Vector3d position, Rotation3d orientation)
    {
        Guard.NotNull(world, nameof(world));
        Guard.Finite(position, nameof(position));
        _world = world;
        Position = position;
        Orientation = orientation;
    }

    /// <summary>The body's position (the origin of its frame), as last set.</summary>
    public Vector3d Position { get; private set; }

    /// <summary>The body's orientation, as last set.</summary>
    public Rotation3d Orientation { get; private set; }

    /// <summary>The attached particles, in the order they were attached.</summary>
    public IReadOnlyList<int> Particles => _particles;

    /// <summary>
    /// Attaches a particle where it is: pins it, with the velocity of the body (zero until the body moves), and keeps
    /// its offset in the body's frame.
    /// </summary>
    /// <exception cref="ArgumentException">The particle is attached already.</exception>
    public void Attach(int particle)
    {
        Guard.ParticleIndex(particle, _world.Count, nameof(particle));
        if (_particles.Contains(particle))
        {
            throw new ArgumentException($"Particle {particle} is attached to this body already.", nameof(particle));
        }

        var offset = Orientation.Inverse().Rotate(_world.GetPosition(particle) - Position);
        _world.Pin(particle);
        _particles.Add(particle);
        _offsets.Add(offset);
    }

    /// <summary>
    /// Lets a particle go: it is unpinned and keeps the velocity it had, the velocity of the body's point. Returns
    /// false when it was not attached.
    /// </summary>
    public bool Detach(int particle)
    {
        _world.ThrowIfStepping(); // before the body forgets the particle: Unpin would refuse only after that
        var index = _particles.IndexOf(particle);
        if (index < 0)
        {
            return false;
        }

        _particles.RemoveAt(index);
        _offsets.RemoveAt(index);
        _world.Unpin(particle);
        return true;
    }

    /// <summary>The point of the body at offset <paramref name="offset"/> (in the body's frame), in world coordinates.</summary>
    public Vector3d PointAt(Vector3d offset) => Position + Orientation.Rotate(offset);

    /// <summary>
    /// Sets the body's pose at the end of the next <paramref name="duration"/> seconds, and gives every attached particle
    /// the velocity that takes it to its point of the body then. Allocates nothing.
    /// </summary>
    /// <exception cref="ArgumentOutOfRangeException">
    /// The pose would take an attached particle beyond the finite numbers, or the duration is so short that a
    /// particle's velocity (target - x) / duration overflows (a particle that stays where it is needs none, at any
    /// duration). Every particle is checked before anything changes: the body and the world are left as they were.
    /// </exception>
    /// <exception cref="InvalidOperationException">
    /// An attached particle was unpinned behind the body's back, or the call comes from inside the world's step.
    /// </exception>
    public void MoveTo(Vector3d position, Rotation3d orientation, double duration)
    {
        _world.ThrowIfStepping();
        Guard.Finite(position, nameof(position));
        Guard.PositiveFinite(duration, nameof(duration));
        for (var a = 0; a < _particles.Count; a++)
        {
            if (!_world.IsPinned(_particles[a]))
            {
                throw new InvalidOperationException(
                    $"Particle {_particles[a]} was unpinned behind the body's back: detach it with Detach.");
            }
        }

        // Every target and every velocity first, so that a pose or a duration that would take one particle beyond the
        // finite numbers changes nothing, not even the pose or the particles before it. The loop below computes the same
        // velocities from the same values.
        for (var a = 0; a < _particles.Count; a++)
        {
            var target = position + orientation.Rotate(_offsets[a]);
            if (!target.IsFinite)
            {
                throw new ArgumentOutOfRangeException(
                    nameof(position),
                    position,
                    $"This pose would take particle {_particles[a]} (offset {_offsets[a]} in the body) to {target}: every "
                    + "attached particle's target must be finite.");
            }

            _ = _world.KinematicVelocity(_particles[a], target, duration, nameof(position));
        }

        Position = position;
        Orientation = orientation;
        for (var a = 0; a < _particles.Count; a++)
        {
            _world.MoveKinematic(_particles[a], PointAt(_offsets[a]), duration);
        }
    }
}
