using System;
using System.Linq;
using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Driver;
using ParticlePhysics.Forces;
using ParticlePhysics.Integrators;
using ParticlePhysics.Tests.Support;

namespace ParticlePhysics.Tests.Engine;

/// <summary>
/// A failed step, or a failed frame of the fixed-timestep driver, leaves what the constraint sets show (the contacts'
/// impact log, the rods' tensions) as it was before, like the world and the integrator
/// (<see cref="IStatefulConstraintSet"/>). Before, the log and the tensions were those of the step that failed.
/// </summary>
public class FailedStepConstraintStateTests
{
    [Theory]
    [InlineData("rk4")]
    [InlineData("semi-implicit-euler")]
    [InlineData("implicit-euler")]
    public void A_step_that_fails_its_divergence_check_leaves_the_impact_log_of_the_last_committed_step(string integrator)
    {
        // Particle 0 hits the ground in step 1, particle 1 in step 2; particle 2 flies at 2 m/s, so a divergence limit
        // of 1.5 m/s fails step 2 after its contact stage has run.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 0.05, 0), new Vector3d(0, -1, 0), 1.0);
        world.AddParticle(new Vector3d(1, 0.15, 0), new Vector3d(0, -1, 0), 1.0);
        world.AddParticle(new Vector3d(0, 10, 0), new Vector3d(2, 0, 0), 1.0);
        var contacts = new ContactSet();
        contacts.Add(PlaneObstacle.Ground(restitution: 0.5));
        world.AddConstraints(contacts);
        var method = IntegratorCatalog.Create(integrator);

        world.Step(method, 0.1);
        var log = contacts.Impacts.ToArray();
        var (count, pairs) = (contacts.ImpactCount, contacts.CandidatePairCount);
        Assert.Equal(1, count);
        Assert.Equal(0, log[0].Particle);

        world.DivergenceLimit = 1.5;
        Assert.Throws<SimulationDivergedException>(() => world.Step(method, 0.1));
        Assert.Equal(count, contacts.ImpactCount);
        Assert.Equal(pairs, contacts.CandidatePairCount);
        Assert.Equal(log, contacts.Impacts.ToArray());

        // The retry, allowed now, logs particle 1's impact.
        world.DivergenceLimit = ParticleWorld.DefaultDivergenceLimit;
        world.Step(method, 0.1);
        Assert.Equal(1, contacts.ImpactCount);
        Assert.Equal(1, contacts.Impacts[0].Particle);
    }

    [Fact]
    public void A_failed_step_leaves_the_rods_tensions_of_the_last_committed_step()
    {
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(1, 0, 0), 1.0);
        world.AddParticle(new Vector3d(0, 10, 0), new Vector3d(2, 0, 0), 1.0);
        world.AddForce(new Gravity());
        var rods = new RodNetwork(world);
        rods.AddAnchoredRod(0, Vector3d.Zero, 1.0);
        world.AddConstraints(rods);
        var method = new RungeKutta4();

        world.Step(method, 0.05);
        var tension = rods.GetTension(0);
        Assert.True(tension > 0.0, $"tension {tension}");

        world.DivergenceLimit = 1.5;
        Assert.Throws<SimulationDivergedException>(() => world.Step(method, 0.05));
        Assert.Equal(BitConverter.DoubleToInt64Bits(tension), BitConverter.DoubleToInt64Bits(rods.GetTension(0)));
    }

    [Fact]
    public void Adding_a_particle_keeps_the_rods_tensions_so_a_failed_step_and_its_retry_agree_with_a_clean_step()
    {
        // Found by the API fuzzer (seed 7): after a particle was added, the next rods call rebuilt their topology and
        // reset every tension to 0. A step that failed had rebuilt it, and its discard put the old tensions back, so
        // its retry (an xpbd step, which evaluates no constraint force) showed them, and the clean twin's step 0s.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(1, 0, 0), 1.0);
        world.AddForce(new Gravity());
        var rods = new RodNetwork(world);
        rods.AddAnchoredRod(0, Vector3d.Zero, 1.0);
        world.AddConstraints(rods);
        world.Step(new RungeKutta4(), 0.05);
        var tension = rods.GetTension(0);
        Assert.True(tension > 0.0, $"tension {tension}");

        world.AddParticle(new Vector3d(0, 5, 0), 1.0);
        world.Step(new Xpbd(2), 0.01);
        Assert.Equal(tension, rods.GetTension(0));
    }

    [Fact]
    public void A_step_that_fails_after_the_contact_stage_leaves_no_pair_state_behind_for_its_retry()
    {
        // Found by the API fuzzer (seed 7, 100,000 operations): with particle collisions switched off after a step that
        // had candidate pairs, a bounce requeued those old pairs, and a pair impact marked its pair as resting. A step
        // that then failed (here a NaN force on a third particle, far away, caught by the divergence check after the
        // contact stage) kept that mark, so its retry skipped the pair while the clean twin's same step collided it.
        // Each step's pair lists are its own now: the failed step, the retry and the clean step agree.
        var twins = new (ParticleWorld World, ContactSet Contacts, FaultyForce Faulty)[2];
        for (var t = 0; t < 2; t++)
        {
            var world = new ParticleWorld();
            world.AddParticle(new Vector3d(0, 0.15, 0), 1);
            world.AddParticle(new Vector3d(0, 0.37, 0), 1);
            world.AddParticle(new Vector3d(0, 5, 0), 1);
            world.SetRadius(0, 0.1);
            world.SetRadius(1, 0.1);
            var faulty = new FaultyForce { Particle = 2 };
            world.AddForce(faulty);
            var contacts = new ContactSet { ParticleCollisions = true };
            contacts.Add(PlaneObstacle.Ground(restitution: 1));
            world.AddConstraints(contacts);
            world.Step(new RungeKutta4(), 0.02);
            Assert.Equal(1, contacts.CandidatePairCount);
            contacts.ParticleCollisions = false;
            world.SetVelocity(0, new Vector3d(0, -10, 0)); // bounces at 5 ms, rises through particle 1
            twins[t] = (world, contacts, faulty);
        }

        var (failing, failingContacts, fault) = twins[0];
        var (clean, cleanContacts, _) = twins[1];
        var before = failing.State.ToArray();
        fault.Arm(Fault.NaN);
        Assert.Throws<SimulationDivergedException>(() => failing.Step(new RungeKutta4(), 0.02));
        Assert.Equal(before, failing.State.ToArray());

        fault.Arm(Fault.None);
        failing.Step(new RungeKutta4(), 0.02);
        clean.Step(new RungeKutta4(), 0.02);
        Assert.Equal(clean.State.ToArray(), failing.State.ToArray());
        Assert.Equal(cleanContacts.ImpactCount, failingContacts.ImpactCount);
        Assert.Equal(cleanContacts.Impacts.ToArray(), failingContacts.Impacts.ToArray());
        Assert.All(failingContacts.Impacts.ToArray(), impact => Assert.True(impact.WithObstacle));
    }

    [Fact]
    public void A_failed_frame_of_the_driver_leaves_the_impact_log_of_before_the_frame()
    {
        // Two fixed steps in one frame: the first logs particle 0's impact and is committed by the world, the second
        // throws from a force; the frame is taken back whole, and so is the log.
        var world = new ParticleWorld();
        world.AddParticle(new Vector3d(0, 0.05, 0), new Vector3d(0, -1, 0), 1.0);
        var faulty = new FaultyForce();
        world.AddForce(faulty);
        var contacts = new ContactSet();
        contacts.Add(PlaneObstacle.Ground(restitution: 0.5));
        world.AddConstraints(contacts);
        var driver = new FixedTimestepDriver(world, new RungeKutta4(), 0.1);

        faulty.Arm(Fault.Throw, afterEvaluations: 4); // rk4 evaluates 4 times per step: the second step throws
        Assert.Throws<InvalidOperationException>(() => driver.Advance(0.2));
        Assert.Equal(0.0, world.Time);
        Assert.Equal(0, contacts.ImpactCount);
        Assert.Equal(0, contacts.Impacts.Length);

        faulty.Arm(Fault.None);
        Assert.Equal(2, driver.Advance(0.2));
        Assert.Equal(0, contacts.ImpactCount); // the second step's own log: the impact was in the first
    }
}
