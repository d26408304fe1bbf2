using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Aerodynamics;

/// <summary>
/// A deterministic gust: the sum of travelling waves u(t, x) = sum a_m sin(2 pi f_m t - k_m . x + phi_m) added to the
/// air's mean velocity. The sines are the library's own (<see cref="DeterministicTrig"/>, + - * / only), so a gusty
/// flag moves with the same bits on .NET, Mono and IL2CPP. Immutable: give the air a new gust to change it.
/// </summary>
/// <remarks>The phase 2 pi f t - k . x + phi must stay within 1.6e6 rad for full accuracy (f = 10 Hz for 7 h).</remarks>
public sealed class Gust
{
    private const int Stride = 8; // 2 pi f, kx, ky, kz, phi, ax, ay, az

    private readonly GustWave[] _waves;
    private readonly double[] _packed;

    /// <summary>A gust of the given waves (at least one; every value finite, frequencies &gt;= 0).</summary>
    public Gust(params GustWave[] waves)
    {
        Guard.NotNull(waves, nameof(waves));
        if (waves.Length == 0)
        {
            throw new ArgumentException("A gust needs at least one wave.", nameof(waves));
        }

        _waves = (GustWave[])waves.Clone();
        _packed = new double[Stride * waves.Length];
        for (var m = 0; m < _waves.Length; m++)
        {
            var wave = _waves[m];
            var name = $"waves[{m}]";
            Guard.Finite(wave.Amplitude, name + ".Amplitude");
            Guard.NonNegativeFinite(wave.Frequency, name + ".Frequency");
            Guard.Finite(wave.WaveVector, name + ".WaveVector");
            Guard.Finite(wave.Phase, name + ".Phase");
            var omega = 2.0 * Math.PI * wave.Frequency;
            if (!DoubleChecks.IsFinite(omega))
            {
                throw new ArgumentOutOfRangeException(name + ".Frequency", wave.Frequency, $"{name}.Frequency times 2 pi must be finite; got {Guard.Format(wave.Frequency)}.");
            }

            var o = Stride * m;
            _packed[o] = omega;
            _packed[o + 1] = wave.WaveVector.X;
            _packed[o + 2] = wave.WaveVector.Y;
            _packed[o + 3] = wave.WaveVector.Z;
            _packed[o + 4] = wave.Phase;
            _packed[o + 5] = wave.Amplitude.X;
            _packed[o + 6] = wave.Amplitude.Y;
            _packed[o + 7] = wave.Amplitude.Z;
        }
    }

    /// <summary>The number of waves.</summary>
    public int WaveCount => _waves.Length;

    /// <summary>Wave <paramref name="index"/>.</summary>
    public GustWave Wave(int index)
    {
        if ((uint)index >= (uint)_waves.Length)
        {
            throw new ArgumentOutOfRangeException(nameof(index), index, $"index must name a wave, 0 to {_waves.Length - 1}; got {index}.");
        }

        return _waves[index];
    }

    /// <summary>The gust's velocity at <paramref name="time"/> and <paramref name="position"/>, m/s.</summary>
    public Vector3d VelocityAt(double time, Vector3d position)
    {
        double x = 0.0, y = 0.0, z = 0.0;
        var packed = _packed;
        for (var o = 0; o + Stride <= packed.Length; o += Stride)
        {
            var phase = (packed[o] * time) - ((packed[o + 1] * position.X) + (packed[o + 2] * position.Y) + (packed[o + 3] * position.Z)) + packed[o + 4];
            var s = DeterministicTrig.Sin(phase);
            x += s * packed[o + 5];
            y += s * packed[o + 6];
            z += s * packed[o + 7];
        }

        return new Vector3d(x, y, z);
    }
}
