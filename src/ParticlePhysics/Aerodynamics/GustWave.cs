namespace ParticlePhysics.Aerodynamics;

/// <summary>
/// One travelling wave of a <see cref="Gust"/>: the air's velocity gains a sin(2 pi f t - k . x + phi) at time t and
/// position x. Its crests move along k at 2 pi f / |k| m/s; k = 0 gives the same gust everywhere at once.
/// </summary>
public readonly struct GustWave
{
    /// <summary>A wave; <see cref="Gust"/> checks its values.</summary>
    /// <param name="amplitude">a, the velocity at a crest, m/s.</param>
    /// <param name="frequency">f, Hz (0: a pattern frozen in time).</param>
    /// <param name="waveVector">k, rad/m (zero: uniform in space).</param>
    /// <param name="phase">phi, rad.</param>
    public GustWave(Vector3d amplitude, double frequency, Vector3d waveVector, double phase = 0.0)
    {
        Amplitude = amplitude;
        Frequency = frequency;
        WaveVector = waveVector;
        Phase = phase;
    }

    /// <summary>a, the velocity at a crest, m/s.</summary>
    public Vector3d Amplitude { get; }

    /// <summary>f, Hz.</summary>
    public double Frequency { get; }

    /// <summary>k, rad/m.</summary>
    public Vector3d WaveVector { get; }

    /// <summary>phi, rad.</summary>
    public double Phase { get; }
}
