using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Contacts;

/// <summary>
/// The contact set and the world's sleeping (<see cref="ParticleWorld.SleepSpeed"/>): a moving particle or obstacle
/// that meets a sleeping particle wakes it before the contact is projected, and the broad phase lists no pair of two
/// sleeping particles.
/// </summary>
public sealed partial class ContactSet
{
    private bool[] _still = Array.Empty<bool>();

    /// <inheritdoc />
    public int Revision => _revision;

    /// <inheritdoc />
    /// <remarks>
    /// None: contacts do not join islands. In a pile of thousands of grains some grain pops or rolls in every half
    /// second, so a pile that is one island never sleeps; instead each particle sleeps on its own, and a sleeping one
    /// wakes when a moving particle touches it or one meets it fast (<see cref="WakeOnImpact"/>).
    /// </remarks>
    public void AddLinks(ParticleIslands islands)
    {
        Guard.NotNull(islands, nameof(islands));
    }

    /// <summary>
    /// A pair of one sleeping and one awake particle that overlap at the prediction (or whose awake one moves its
    /// radius in the substep): the sleeping one's island wakes, so that the projection that follows meets its masses,
    /// if the awake one moved faster than the wake speed in the last step (an impact, or the support knocked from under
    /// a sleeping box), or if it is fresh (woken in this step, added or set by the host) and approaches faster than
    /// that. A particle at rest on it, which does not move, does not wake it.
    /// </summary>
    private static void WakeOnImpact(in ConstraintContext context, ISleepingParticles sleeping, int a, int b, Span<double> radii, bool fast)
    {
        var asleep = sleeping.IsAsleep(a);
        if (asleep == sleeping.IsAsleep(b))
        {
            return;
        }

        int still = asleep ? a : b, mover = asleep ? b : a;
        var moved = sleeping.MovedLastStep(mover);
        if (!moved && !sleeping.IsFresh(mover))
        {
            return;
        }

        var x = context.Positions;
        var reach = Radius(radii, a) + Radius(radii, b);
        var d = Read(x, still) - Read(x, mover);
        if (!fast && !(Vector3d.Dot(d, d) < reach * reach))
        {
            return;
        }

        if (!moved)
        {
            var start = Read(context.StartPositions.ForReading(), still) - Read(context.StartPositions.ForReading(), mover);
            var distance = start.Length;
            var approach = distance > 0.0 ? Vector3d.Dot(Read(context.StartVelocities.ForReading(), mover), start) / distance : 0.0;
            if (!(approach > sleeping.WakeSpeed))
            {
                return;
            }
        }

        sleeping.Wake(still);
    }

    /// <summary>Which particles sleep, for the broad phase (null when none does): their pairs with each other are not listed.</summary>
    private bool[]? StillParticles(in ConstraintContext context)
    {
        if (context.Sleeping is not { } sleeping)
        {
            return null;
        }

        var n = context.Count;
        if (_still.Length < n)
        {
            _still = new bool[n];
        }

        var any = false;
        var inverseMasses = context.InverseMasses.ForReading();
        for (var i = 0; i < n; i++)
        {
            var asleep = inverseMasses[i] == 0.0 && sleeping.IsAsleep(i);
            _still[i] = asleep;
            any |= asleep;
            if (asleep && _anyGrains && IsGrain(i))
            {
                _spin[i] = Vector3d.Zero; // a sleeping grain is at rest, and wakes without the spin it fell asleep with
            }
        }

        return any ? _still : null;
    }

    private bool AnyObstacleMoves()
    {
        for (var k = 0; k < _obstacles.Count; k++)
        {
            if (_obstacles[k].Velocity != Vector3d.Zero)
            {
                return true;
            }
        }

        return false;
    }

    /// <summary>
    /// Whether a sleeping particle ends the substep inside an obstacle that moves (a collider driven into a sleeping
    /// pile): then its island is woken and it is projected as any other.
    /// </summary>
    private bool WokenByMovingObstacle(in ConstraintContext context, ISleepingParticles sleeping, int i, double radius, double end)
    {
        if (!sleeping.IsAsleep(i))
        {
            return false;
        }

        var position = Read(context.Positions, i);
        var candidates = ObstaclesNear(i, Read(context.StartPositions.ForReading(), i), position, TouchReach(radius), -1);
        for (var c = 0; c < candidates; c++)
        {
            var obstacle = _obstacles[_candidates[c]];
            if (obstacle.Velocity != Vector3d.Zero && EndGap(obstacle, position, end, radius, out _) < 0.0)
            {
                sleeping.Wake(i);
                return true;
            }
        }

        return false;
    }
}
