using System;
using System.Globalization;
using System.Linq;
using System.Threading;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Tests.Engine;

/// <summary>
/// Bad input to the contacts, rods and kinematic bodies: refused with the value named and what is allowed, nothing
/// changed; values that are valid but whose squares overflow or underflow give the answer, not a refusal.
/// </summary>
public class NewApiBadInputTests
{
    [Theory]
    [InlineData(1e-320)]
    [InlineData(4.9e-324)]
    public void A_rod_or_cable_length_whose_inverse_overflows_is_refused_like_a_mass(double length)
    {
        // It was accepted, and the first step's relative violation |d - L| / L was infinite.
        var world = TwoParticles();
        var rods = new RodNetwork(world);
        foreach (var add in new Action[]
        {
            () => rods.AddRod(0, 1, length), () => rods.AddCable(0, 1, length),
            () => rods.AddAnchoredRod(0, Vector3d.Zero, length), () => rods.AddAnchoredCable(0, Vector3d.Zero, length),
        })
        {
            var e = Assert.Throws<ArgumentOutOfRangeException>("length", add);
            Assert.Contains("inverse is finite", e.Message, StringComparison.Ordinal);
            Assert.Contains(length.ToString("R", CultureInfo.InvariantCulture), e.Message, StringComparison.Ordinal);
        }

        Assert.Equal(0, rods.Count);
        rods.AddRod(0, 1, 5.6e-309); // the smallest such length is accepted
    }

    [Theory]
    [InlineData(1e160)]
    [InlineData(1.35e154)]
    [InlineData(double.MaxValue)]
    public void A_rod_or_cable_length_whose_square_overflows_is_refused_like_a_capsule(double length)
    {
        // Issue 27, item 9: AddAnchoredRod(p, anchor, 1e160) with the particle exactly that far was accepted, then every
        // rk4 and xpbd step failed with NaN: the constraint C = (|d|^2 - L^2) / 2 squares the length.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(length, 0, 0), 1);
        world.AddParticle(new Vector3d(0, 0, 0), 1);
        var rods = new RodNetwork(world);
        foreach (var add in new Action[]
        {
            () => rods.AddRod(0, 1, length), () => rods.AddCable(0, 1, length),
            () => rods.AddAnchoredRod(0, Vector3d.Zero, length), () => rods.AddAnchoredCable(0, Vector3d.Zero, length),
        })
        {
            var e = Assert.Throws<ArgumentOutOfRangeException>("length", add);
            Assert.Contains("square", e.Message, StringComparison.Ordinal);
            Assert.Contains(length.ToString("R", CultureInfo.InvariantCulture), e.Message, StringComparison.Ordinal);
        }

        Assert.Equal(0, rods.Count);
    }

    [Theory]
    [InlineData("rk4")]
    [InlineData("semi-implicit-euler")]
    [InlineData("xpbd")]
    public void A_rod_of_1e150_m_steps(string integrator)
    {
        // The longest rods accepted square to a finite number, and step: a particle on a rod of 1e150 m swinging at 1 m/s.
        const double length = 1e150;
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(length, 0, 0), new Vector3d(0, 1, 0), 1);
        var rods = new RodNetwork(world);
        rods.AddAnchoredRod(0, Vector3d.Zero, length);
        world.AddConstraints(rods);
        var method = IntegratorCatalog.Create(integrator);
        for (var s = 0; s < 10; s++)
        {
            world.Step(method, 0.01);
        }

        Assert.Equal(length, world.GetPosition(0).X, length * 1e-15);
        Assert.Equal(0.1, world.GetPosition(0).Y, 12);
    }

    [Fact]
    public void Directions_whose_length_overflows_or_underflows_are_normalised_not_refused()
    {
        // (1e300, 1e300, 0) and (0, 1e-320, 0) are finite, non-zero directions; they were refused as "not a finite
        // non-zero vector" because their length overflowed to infinity or underflowed to 0.
        var diagonal = new PlaneObstacle(Vector3d.Zero, new Vector3d(1, 1, 0)).Normal;
        Assert.Equal(diagonal, new PlaneObstacle(Vector3d.Zero, new Vector3d(1e300, 1e300, 0)).Normal);
        Assert.Equal(new Vector3d(0, 1, 0), new PlaneObstacle(Vector3d.Zero, new Vector3d(0, 1e-320, 0)).Normal);

        Assert.Equal(new Rotation3d(1, 1, 0, 0), new Rotation3d(1e200, 1e200, 0, 0));
        Assert.Equal(new Rotation3d(1, 0, 0, 0), new Rotation3d(1e-200, 0, 0, 0));

        // An axis of length 1e300 gave a wrong rotation (its components divided by an infinite length: no rotation).
        var about = Rotation3d.FromAxisAngle(new Vector3d(1, 1, 0), 1.0).Rotate(new Vector3d(0, 0, 1));
        var overflowing = Rotation3d.FromAxisAngle(new Vector3d(1e300, 1e300, 0), 1.0).Rotate(new Vector3d(0, 0, 1));
        Assert.True((about - overflowing).Length < 1e-15, $"{about} vs {overflowing}");

        Assert.Throws<ArgumentOutOfRangeException>("Normal", () => new PlaneObstacle(Vector3d.Zero, Vector3d.Zero));
        Assert.Throws<ArgumentException>(() => new Rotation3d(0, 0, 0, 0));
        Assert.Throws<ArgumentException>(() => new Rotation3d(double.NaN, 1, 0, 0));
    }

    [Fact]
    public void A_rotations_error_prints_its_numbers_in_the_invariant_culture()
    {
        var culture = Thread.CurrentThread.CurrentCulture;
        try
        {
            Thread.CurrentThread.CurrentCulture = new CultureInfo("fr-FR");
            var e = Assert.Throws<ArgumentException>(() => new Rotation3d(double.NaN, 0.5, 0, 0));
            Assert.Contains("0.5", e.Message, StringComparison.Ordinal);
            var axis = Assert.Throws<ArgumentException>(() => Rotation3d.FromAxisAngle(new Vector3d(1, 0, 0), double.NaN));
            Assert.DoesNotContain(",5", axis.Message, StringComparison.Ordinal);
        }
        finally
        {
            Thread.CurrentThread.CurrentCulture = culture;
        }
    }

    [Fact]
    public void A_capsule_whose_segment_length_overflows_is_refused_and_one_far_from_the_origin_is_not()
    {
        // Ends 2e308 apart made every distance NaN, and every step with the capsule fail.
        var e = Assert.Throws<ArgumentOutOfRangeException>(
            "End", () => new CapsuleObstacle(new Vector3d(-1e308, 0, 0), new Vector3d(1e308, 0, 0), 1));
        Assert.Contains("too long", e.Message, StringComparison.Ordinal);
        var capsule = new CapsuleObstacle(new Vector3d(0, 0, 0), new Vector3d(1, 0, 0), 1);
        Assert.Throws<ArgumentOutOfRangeException>("End", () => capsule.End = new Vector3d(1e200, 0, 0));
        Assert.Equal(new Vector3d(1, 0, 0), capsule.End);

        // Far from the origin, with a short segment: accepted (the ends alone would square to infinity).
        var far = new CapsuleObstacle(new Vector3d(1e200, 0, 0), new Vector3d(1e200, 1, 0), 1);
        Assert.Equal(new Vector3d(1e200, 1, 0), far.End);
    }

    [Fact]
    public void A_body_pose_that_would_take_a_particle_beyond_the_finite_numbers_changes_nothing()
    {
        // It moved the body and the particles before the first infinite target threw.
        var world = TwoParticles();
        world.SetPosition(1, new Vector3d(1e308, 0, 0));
        var body = new KinematicBody(world, Vector3d.Zero, Rotation3d.Identity);
        body.Attach(0);
        body.Attach(1);
        var state = world.State.ToArray();
        var e = Assert.Throws<ArgumentOutOfRangeException>("position", () => body.MoveTo(new Vector3d(1e308, 0, 0), Rotation3d.Identity, 1.0));
        Assert.Contains("particle 1", e.Message, StringComparison.Ordinal);
        Assert.Equal(Vector3d.Zero, body.Position);
        Assert.Equal(state, world.State.ToArray());
        world.Step(new SemiImplicitEuler(), 0.1);
        Assert.Equal(state.Take(6), world.State.ToArray().Take(6)); // particle 0 was not set moving
    }

    [Theory]
    [InlineData(1e-308)]
    [InlineData(double.Epsilon)]
    public void A_body_move_whose_velocity_overflows_changes_nothing_and_names_the_duration(double duration)
    {
        // Issue 27, item 2: the pose was set and particle 0 given its velocity, 1e-300 / 1e-308 = 1e8 m/s, before
        // particle 1's, 2 / 1e-308, overflowed; the error said "target must have finite components; got (Infinity,
        // NaN, NaN)". With double.Epsilon the pose moved and the call threw too.
        var world = new ParticleWorld();
        world.AddParticle(Vector3d.Zero, 1); // at the body's origin
        world.AddParticle(new Vector3d(1, 0, 0), 1);
        var body = new KinematicBody(world, Vector3d.Zero, Rotation3d.Identity);
        body.Attach(0);
        body.Attach(1);
        var state = world.State.ToArray();
        var halfTurn = Rotation3d.FromAxisAngle(new Vector3d(0, 0, 1), Math.PI);
        var e = Assert.Throws<ArgumentOutOfRangeException>(
            "duration", () => body.MoveTo(new Vector3d(1e-300, 0, 0), halfTurn, duration));
        Assert.Contains("velocity", e.Message, StringComparison.Ordinal);
        Assert.Contains(duration.ToString("R", CultureInfo.InvariantCulture), e.Message, StringComparison.Ordinal);
        Assert.DoesNotContain("NaN", e.Message, StringComparison.Ordinal);
        Assert.Equal(Vector3d.Zero, body.Position);
        Assert.Equal(Rotation3d.Identity, body.Orientation);
        Assert.Equal(state, world.State.ToArray());

        // The same pose in any duration needs no velocity at all: accepted, at rest.
        body.MoveTo(Vector3d.Zero, Rotation3d.Identity, duration);
        Assert.Equal(state, world.State.ToArray());
    }

    [Theory]
    [InlineData(double.Epsilon)]
    [InlineData(1e-308)]
    [InlineData(1e-300)]
    public void A_kinematic_move_to_where_the_particle_is_stops_it_for_any_duration(double duration)
    {
        // Issue 27, item 3: the velocity was computed as (target - x) * (1 / duration), and 1 / 5e-324 = infinity made
        // 0 * infinity = NaN: refused with "target must have finite components; got (NaN, NaN, NaN)".
        var world = TwoParticles();
        world.Pin(0, new Vector3d(1, 2, 3));
        world.MoveKinematic(0, world.GetPosition(0), duration);
        Assert.Equal(Vector3d.Zero, world.GetVelocity(0));

        // A move that really needs more than the finite numbers names the duration and the velocity, and changes nothing.
        world.Pin(0, new Vector3d(1, 2, 3));
        var e = Assert.Throws<ArgumentOutOfRangeException>(
            "duration", () => world.MoveKinematic(0, world.GetPosition(0) + new Vector3d(0, 1e300, 0), duration));
        Assert.Contains("velocity", e.Message, StringComparison.Ordinal);
        Assert.DoesNotContain("NaN", e.Message, StringComparison.Ordinal);
        Assert.Equal(new Vector3d(1, 2, 3), world.GetVelocity(0));

        // A target so far that target - x itself overflows names the target.
        world.SetPosition(0, new Vector3d(-1e308, 0, 0));
        var far = Assert.Throws<ArgumentOutOfRangeException>("target", () => world.MoveKinematic(0, new Vector3d(1e308, 0, 0), 1));
        Assert.Contains("overflows", far.Message, StringComparison.Ordinal);
        Assert.Equal(new Vector3d(1, 2, 3), world.GetVelocity(0));
    }

    [Fact]
    public void A_kinematic_velocity_keeps_its_bits_for_ordinary_durations()
    {
        // (target - x) times 1 / duration, as before the fix for durations whose inverse overflows: runs that drive
        // anchors (the Unity sample, the runtime comparison's body) keep their results.
        var world = TwoParticles();
        world.Pin(0);
        var target = new Vector3d(0.3, 1.7, -0.2);
        const double duration = 1.0 / 60;
        world.MoveKinematic(0, target, duration);
        Assert.Equal((target - new Vector3d(0, 1, 0)) * (1.0 / duration), world.GetVelocity(0));
    }

    [Fact]
    public void Radii_and_rods_cannot_be_changed_from_inside_the_worlds_step()
    {
        var world = TwoParticles();
        var rods = new RodNetwork(world);
        var calls = new Action[] { () => world.SetRadius(0, 0.5), () => rods.AddRod(0, 1, 1.0) };
        foreach (var call in calls)
        {
            var meddler = new Meddler(call);
            world.AddForce(meddler);
            Assert.Throws<InvalidOperationException>(() => world.Step(new RungeKutta4(), 0.01));
            world.RemoveForce(meddler);
        }

        Assert.Equal(0.0, world.GetRadius(0));
        Assert.Equal(0, rods.Count);
        Assert.Equal(0.0, world.Time);
    }

    private static ParticleWorld TwoParticles()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 1, 0), 1);
        world.AddParticle(new Vector3d(1, 1, 0), 1);
        return world;
    }

    /// <summary>A user force that calls something on the world while it is evaluated.</summary>
    private sealed class Meddler : IForceGenerator
    {
        private readonly Action _call;

        public Meddler(Action call)
        {
            _call = call;
        }

        public void AddForces(in ParticleState state, Span<double> forces) => _call();
    }
}
