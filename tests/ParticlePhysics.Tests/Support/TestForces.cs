using System;

namespace ParticlePhysics.Tests.Support;

/// <summary>
/// A time-dependent drive F_i = m_i A cos(omega t) along x, used to catch integrators that evaluate a stage at the
/// wrong time. Exact, for a free particle starting at x0 with velocity v0 along x:
/// x(t) = x0 + v0 t + (A / omega^2)(1 - cos omega t), v(t) = v0 + (A / omega) sin omega t.
/// </summary>
internal sealed class HarmonicDrive : IForceGenerator
{
    public HarmonicDrive(double amplitude, double angularFrequency)
    {
        Amplitude = amplitude;
        AngularFrequency = angularFrequency;
    }

    public double Amplitude { get; }

    public double AngularFrequency { get; }

    public void AddForces(in ParticleState state, Span<double> forces)
    {
        var drive = Amplitude * Math.Cos(AngularFrequency * state.Time);
        for (var i = 0; i < state.Count; i++)
        {
            forces[3 * i] += state.Masses[i] * drive;
        }
    }

    public void ExactState(double x0, double v0, double t, Span<double> state)
    {
        var w = AngularFrequency;
        state.Clear();
        state[0] = x0 + (v0 * t) + (Amplitude / (w * w) * (1 - Math.Cos(w * t)));
        state[3] = v0 + (Amplitude / w * Math.Sin(w * t));
    }
}
