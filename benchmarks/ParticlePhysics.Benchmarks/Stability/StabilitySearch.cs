using System;
using ParticlePhysics.Integrators;

namespace ParticlePhysics.Benchmarks.Stability;

/// <summary>
/// Finds, by bisection, the largest time step at which an integrator keeps the cloth stable and sane for
/// <see cref="SimulatedSeconds"/> of simulated time from rest.
/// </summary>
/// <remarks>
/// A trial fails when a step throws <see cref="SimulationDivergedException"/> (a value beyond
/// <see cref="ParticleWorld.DivergenceLimit"/> or not finite) or when a particle ends up farther than
/// <see cref="SaneDistance"/> from the nearest pin (the cloth is 1 m wide and hangs about 1.5 m: anything beyond is
/// a blow-up that has not yet reached the limit). Explicit methods lose stability abruptly past a threshold, so
/// "stable at dt" is monotone in practice; the search halves from <see cref="LargestTried"/> until a trial passes,
/// then bisects geometrically to <see cref="RelativePrecision"/>. The result is the largest dt that passed.
/// </remarks>
internal static class StabilitySearch
{
    public const double SimulatedSeconds = 2.0;
    public const double SaneDistance = 3.0;
    public const double LargestTried = 0.02;
    public const double SmallestTried = 1e-6;
    public const double RelativePrecision = 0.01;

    /// <summary>The outcome of one trial.</summary>
    public readonly record struct Trial(bool Stable, double FarthestFromPin, string Reason);

    /// <summary>The largest stable dt (at most <see cref="LargestTried"/>), or 0 if none down to <see cref="SmallestTried"/>.</summary>
    public static double LargestStableTimeStep(string integrator, int particlesPerSide, Action<double, Trial>? log = null)
    {
        var high = LargestTried;
        var first = Run(integrator, particlesPerSide, high);
        log?.Invoke(high, first);
        if (first.Stable)
        {
            return high;
        }

        var low = high / 2;
        while (true)
        {
            var trial = Run(integrator, particlesPerSide, low);
            log?.Invoke(low, trial);
            if (trial.Stable)
            {
                break;
            }

            high = low;
            low /= 2;
            if (low < SmallestTried)
            {
                return 0;
            }
        }

        while (high / low > 1 + RelativePrecision)
        {
            var middle = Math.Sqrt(low * high);
            var trial = Run(integrator, particlesPerSide, middle);
            log?.Invoke(middle, trial);
            if (trial.Stable)
            {
                low = middle;
            }
            else
            {
                high = middle;
            }
        }

        return low;
    }

    /// <summary>Runs the cloth from rest for <see cref="SimulatedSeconds"/> at <paramref name="dt"/>.</summary>
    public static Trial Run(string integrator, int particlesPerSide, double dt)
    {
        var cloth = new ClothFixture(particlesPerSide);
        var method = IntegratorCatalog.Create(integrator);
        var steps = (int)Math.Ceiling(SimulatedSeconds / dt);
        var farthest = 0.0;
        try
        {
            for (var s = 1; s <= steps; s++)
            {
                cloth.System.Step(method, dt);
                if (s % 64 == 0 || s == steps)
                {
                    farthest = FarthestFromPin(cloth.System);
                    if (!(farthest <= SaneDistance))
                    {
                        return new Trial(false, farthest, $"a particle {farthest:G3} m from the pins at t = {cloth.System.Time:G4} s");
                    }
                }
            }
        }
        catch (SimulationDivergedException e)
        {
            return new Trial(false, double.PositiveInfinity, $"diverged at t = {e.Time:G4} s");
        }

        return new Trial(true, farthest, "stable");
    }

    /// <summary>The largest distance from a particle to its nearest pinned particle, in metres.</summary>
    public static double FarthestFromPin(ParticleWorld system)
    {
        Span<int> pins = stackalloc int[8];
        var pinCount = 0;
        for (var i = 0; i < system.Count && pinCount < pins.Length; i++)
        {
            if (system.IsPinned(i))
            {
                pins[pinCount++] = i;
            }
        }

        var x = system.Positions;
        var farthest = 0.0;
        for (var i = 0; i < system.Count; i++)
        {
            var nearest = double.PositiveInfinity;
            for (var p = 0; p < pinCount; p++)
            {
                var o = 3 * pins[p];
                double dx = x[3 * i] - x[o], dy = x[(3 * i) + 1] - x[o + 1], dz = x[(3 * i) + 2] - x[o + 2];
                nearest = Math.Min(nearest, Math.Sqrt((dx * dx) + (dy * dy) + (dz * dz)));
            }

            farthest = Math.Max(farthest, nearest);
        }

        return farthest;
    }
}
