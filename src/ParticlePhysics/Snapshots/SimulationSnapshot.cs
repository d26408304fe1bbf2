using System;
using System.Text;
using ParticlePhysics.Integrators;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Snapshots;

/// <summary>
/// The whole dynamic state of a <see cref="ParticleWorld"/> (time, positions, velocities, masses, pins, radii) and of its
/// integrator (<see cref="IStatefulIntegrator"/>), captured and restored bit for bit: for save games, replays and
/// rollback. It does not hold the force generators: they are the scene's configuration, which the host rebuilds (the
/// same builder code) before restoring.
/// </summary>
/// <remarks>
/// In memory, <see cref="CaptureFrom"/> and <see cref="RestoreTo"/> reuse the snapshot's arrays, so a rollback buffer of
/// snapshots allocates nothing per frame. On a stream, <see cref="WriteTo"/> and <see cref="ReadFrom"/> use a
/// versioned binary format, all little-endian:
/// <code>
/// offset  size  field
///  0       4    magic "PPSN"
///  4       2    format version (2; version 1, without radii, is still read: its particles get radius 0)
///  6       2    flags (0)
///  8       4    particle count n
/// 12       4    integrator name length b, in UTF-8 bytes (0: captured without an integrator)
/// 16       4    integrator state length m, in doubles
/// 20       8    time
/// 28       b    integrator name (UTF-8)
///          48 n state vector [positions | velocities], 6 doubles per particle
///          8 n  masses
///          n    pinned flags (0 or 1)
///          8 n  radii (version 2 on)
///          8 m  integrator state
///          4    CRC-32 of every byte before it
/// </code>
/// Reading checks everything (magic, version, counts, length, checksum, then every value) before it returns, and
/// <see cref="RestoreTo"/> checks the snapshot against the system before it writes: a bad stream or a mismatched
/// system throws and leaves the live system untouched.
/// </remarks>
public sealed partial class SimulationSnapshot
{
    /// <summary>The format version that <see cref="WriteTo"/> writes and <see cref="ReadFrom"/> reads.</summary>
    public const int FormatVersion = 2;

    /// <summary>The oldest format version that <see cref="ReadFrom"/> still reads (1: without radii).</summary>
    public const int OldestReadableVersion = 1;

    /// <summary>
    /// The largest integrator state, in doubles, that the format accepts for <paramref name="particleCount"/>
    /// particles: <see cref="IntegratorStateLimit.MaxLength"/>, 1024 plus 24 per particle (implicit Euler's warm
    /// start is up to eight vectors over the particles: the last four steps' velocity changes and their products).
    /// </summary>
    public static int MaxIntegratorStateLength(int particleCount) => IntegratorStateLimit.MaxLength(particleCount);

    /// <summary>The largest integrator name, in UTF-8 bytes, that the binary format accepts.</summary>
    public const int MaxIntegratorNameLength = 256;

    private double[] _state = Array.Empty<double>();
    private double[] _masses = Array.Empty<double>();
    private bool[] _pinned = Array.Empty<bool>();
    private double[] _radii = Array.Empty<double>();
    private double[] _integratorState = Array.Empty<double>();

    private SimulationSnapshot()
    {
    }

    /// <summary>The number of particles.</summary>
    public int ParticleCount => _masses.Length;

    /// <summary>The simulated time, in seconds.</summary>
    public double Time { get; private set; }

    /// <summary>The state vector [positions | velocities], 6 values per particle, as <see cref="ParticleWorld.State"/>.</summary>
    public ReadOnlySpan<double> State => _state;

    /// <summary>The masses, one per particle.</summary>
    public ReadOnlySpan<double> Masses => _masses;

    /// <summary>The pinned flags, one per particle.</summary>
    public ReadOnlySpan<bool> Pinned => _pinned;

    /// <summary>The radii, one per particle (0 for a snapshot read from format version 1).</summary>
    public ReadOnlySpan<double> Radii => _radii;

    /// <summary>The <see cref="IIntegrator.Name"/> of the integrator captured with the system, or null.</summary>
    public string? IntegratorName { get; private set; }

    /// <summary>The integrator's state (<see cref="IStatefulIntegrator"/>), empty for a stateless one.</summary>
    public ReadOnlySpan<double> IntegratorState => _integratorState;

    /// <summary>Captures <paramref name="system"/> and, optionally, the integrator that steps it.</summary>
    /// <param name="system">The system.</param>
    /// <param name="integrator">
    /// The integrator, or null: needed for a bit-exact continuation with an integrator that carries state
    /// (<see cref="DormandPrince45"/>); its name is recorded either way and checked on restore.
    /// </param>
    public static SimulationSnapshot Capture(ParticleWorld system, IIntegrator? integrator = null)
    {
        var snapshot = new SimulationSnapshot();
        snapshot.CaptureFrom(system, integrator);
        return snapshot;
    }

    /// <summary>
    /// Overwrites this snapshot with the state of <paramref name="system"/> (and <paramref name="integrator"/>),
    /// reusing its arrays when the sizes match: allocates nothing when capturing the same system again.
    /// </summary>
    public void CaptureFrom(ParticleWorld system, IIntegrator? integrator = null)
    {
        Guard.NotNull(system, nameof(system));
        var n = system.Count;
        var stateful = integrator as IStatefulIntegrator;
        var m = stateful?.StateLength ?? 0;
        if (m < 0 || m > MaxIntegratorStateLength(system.Count))
        {
            throw new ArgumentException(
                $"The integrator's StateLength must be 0 to {MaxIntegratorStateLength(system.Count)}; got {m}.",
                nameof(integrator));
        }

        var name = integrator?.Name;
        if (name is not null && Encoding.UTF8.GetByteCount(name) > MaxIntegratorNameLength)
        {
            throw new ArgumentException(
                $"The integrator's name must be at most {MaxIntegratorNameLength} UTF-8 bytes long.", nameof(integrator));
        }

        var state = Resize(_state, 6 * n);
        var masses = Resize(_masses, n);
        var pinned = _pinned.Length == n ? _pinned : new bool[n];
        var radii = Resize(_radii, n);
        var integratorState = Resize(_integratorState, m);
        stateful?.WriteState(integratorState);
        system.State.CopyTo(state);
        system.Masses.CopyTo(masses);
        system.Radii.CopyTo(radii);
        for (var i = 0; i < n; i++)
        {
            pinned[i] = system.IsPinned(i);
        }

        _state = state;
        _masses = masses;
        _pinned = pinned;
        _radii = radii;
        _integratorState = integratorState;
        IntegratorName = name;
        Time = system.Time;
    }

    /// <summary>
    /// Restores the captured state into <paramref name="system"/> (and <paramref name="integrator"/>), bit for bit.
    /// Everything is checked first; a rejected call throws and changes nothing. Allocates nothing. A
    /// <see cref="Driver.FixedTimestepDriver"/> running the system should then be <see cref="Driver.FixedTimestepDriver.Reset"/>.
    /// </summary>
    /// <param name="system">A system with the same number of particles, and the same force generators for the same run.</param>
    /// <param name="integrator">
    /// The integrator to restore too, or null for the particles only. It must have the captured integrator's name;
    /// one that carries state (<see cref="IStatefulIntegrator"/>) needs a snapshot captured with it.
    /// </param>
    /// <exception cref="ArgumentException">The particle count, integrator name or integrator state does not match.</exception>
    public void RestoreTo(ParticleWorld system, IIntegrator? integrator = null)
    {
        Guard.NotNull(system, nameof(system));
        system.ThrowIfStepping();
        if (system.Count != ParticleCount)
        {
            throw new ArgumentException(
                $"The snapshot holds {ParticleCount} particles but the system has {system.Count}: "
                + "restore into a system built the same way.",
                nameof(system));
        }

        if (integrator is not null)
        {
            if (IntegratorName is not null && integrator.Name != IntegratorName)
            {
                throw new ArgumentException(
                    $"The snapshot was captured with the integrator '{IntegratorName}', not '{integrator.Name}'.",
                    nameof(integrator));
            }

            if (integrator is IStatefulIntegrator stateful)
            {
                if (IntegratorName is null)
                {
                    throw new ArgumentException(
                        $"The integrator '{integrator.Name}' carries state, but the snapshot was captured without an "
                        + "integrator: pass null to restore the particles only.",
                        nameof(integrator));
                }

                // Checks the length and the values before changing anything (the length may follow the system, as an
                // implicit integrator's warm start does); the particle data below was checked when captured or read.
                stateful.ReadState(_integratorState);
            }
            else if (_integratorState.Length != 0)
            {
                throw new ArgumentException(
                    $"The snapshot holds integrator state, but '{integrator.Name}' does not take any.", nameof(integrator));
            }
        }

        // Nothing below can fail: the masses and the state were checked when captured or read, and the world is not
        // in a step (checked above), so the integrator's state, read first, is never left restored alone.
        for (var i = 0; i < _masses.Length; i++)
        {
            system.SetMass(i, _masses[i]);
            system.SetRadius(i, _radii[i]);
            if (_pinned[i])
            {
                system.Pin(i);
            }
            else
            {
                system.Unpin(i);
            }
        }

        system.SetState(_state);
        system.Time = Time;
    }
}
