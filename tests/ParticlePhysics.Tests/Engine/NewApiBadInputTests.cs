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
