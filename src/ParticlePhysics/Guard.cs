using System;
using System.Globalization;
using ParticlePhysics.Numerics;

namespace ParticlePhysics;

/// <summary>
/// Argument checks shared by every public entry point. Each throws before anything is changed, with a message
/// that names the parameter, the value received and what is allowed.
/// </summary>
internal static class Guard
{
    public static string Format(double value) => value.ToString("R", CultureInfo.InvariantCulture);

    public static void PositiveFinite(double value, string name, string? hint = null)
    {
        if (!(value > 0.0) || !DoubleChecks.IsFinite(value))
        {
            throw new ArgumentOutOfRangeException(
                name, value, $"{name} must be a positive finite number; got {Format(value)}.{Suffix(hint)}");
        }
    }

    public static void NonNegativeFinite(double value, string name)
    {
        if (!(value >= 0.0) || !DoubleChecks.IsFinite(value))
        {
            throw new ArgumentOutOfRangeException(
                name, value, $"{name} must be a finite number >= 0; got {Format(value)}.");
        }
    }

    public static void Finite(double value, string name)
    {
        if (!DoubleChecks.IsFinite(value))
        {
            throw new ArgumentOutOfRangeException(name, value, $"{name} must be a finite number; got {Format(value)}.");
        }
    }

    public static void Finite(Vector3d value, string name)
    {
        if (!value.IsFinite)
        {
            throw new ArgumentOutOfRangeException(
                name, value, $"{name} must have finite components; got {value}.");
        }
    }

    /// <summary>
    /// A step of <paramref name="dt"/> from <paramref name="time"/> must end at a finite time (a state at t = inf cannot
    /// be saved or read back) that is later than its start: a dt that vanishes against t (1e-3 from t = 1e20) would be a
    /// step that moves nothing yet reports success, and lets an integrator keep state from a step that never ran.
    /// </summary>
    public static void FiniteEndTime(double time, double dt)
    {
        var end = time + dt;
        if (!DoubleChecks.IsFinite(end))
        {
            throw new ArgumentOutOfRangeException(
                "dt",
                dt,
                $"dt = {Format(dt)} from t = {Format(time)} would end the step at t = {Format(end)}; the end time must be finite.");
        }

        if (!(end > time))
        {
            throw new ArgumentOutOfRangeException(
                "dt",
                dt,
                $"dt = {Format(dt)} does not advance t = {Format(time)}: t + dt rounds to t. Take a larger dt, or start the time nearer 0.");
        }
    }

    /// <summary>
    /// A mass: positive, finite, and large enough that its inverse 1 / m is finite too (m &gt;= 1 / double.MaxValue,
    /// about 5.6e-309), since every integrator divides by it.
    /// </summary>
    public static void Mass(double mass, string name)
    {
        PositiveFinite(mass, name, "Pin the particle to make it immovable.");
        if (!DoubleChecks.IsFinite(1.0 / mass))
        {
            throw new ArgumentOutOfRangeException(
                name,
                mass,
                $"{name} must be at least {Format(SmallestMass)} kg, so that its inverse is finite; got {Format(mass)}.");
        }
    }

    /// <summary>A positive finite <paramref name="value"/> whose inverse is finite too (a length or mass that is divided by).</summary>
    public static void PositiveWithFiniteInverse(double value, string name, string unit)
    {
        PositiveFinite(value, name);
        if (!DoubleChecks.IsFinite(1.0 / value))
        {
            throw new ArgumentOutOfRangeException(
                name,
                value,
                $"{name} must be at least {Format(SmallestMass)} {unit}, so that its inverse is finite; got {Format(value)}.");
        }
    }

    /// <summary>
    /// <paramref name="value"/> / |value| for a finite non-zero vector, also when |value| overflows or underflows
    /// (computed then from value scaled by its largest component); a vector whose length is a normal double is divided
    /// by it directly (one rounding fewer).
    /// </summary>
    public static Vector3d Direction(Vector3d value, string name)
    {
        var length = value.Length;
        if (value.IsFinite && length > 0.0 && DoubleChecks.IsFinite(length) && length >= 1e-150)
        {
            return value / length;
        }

        var scale = Math.Max(Math.Abs(value.X), Math.Max(Math.Abs(value.Y), Math.Abs(value.Z)));
        if (!value.IsFinite || !(scale > 0.0))
        {
            throw new ArgumentOutOfRangeException(name, value, $"{name} must be a finite non-zero vector; got {value}.");
        }

        var scaled = value / scale;
        return scaled / scaled.Length;
    }

    /// <summary>The smallest mass whose inverse is finite: the double just above 1 / double.MaxValue (whose own inverse overflows).</summary>
    public const double SmallestMass = 5.56268464626801e-309;

    public static void ParticleIndex(int index, int count, string name)
    {
        if ((uint)index >= (uint)count)
        {
            throw new ArgumentOutOfRangeException(
                name, index, $"{name} must name an existing particle, 0 to {count - 1}; got {index}.");
        }
    }

    public static void DistinctParticles(int first, int second, string name)
    {
        if (first == second)
        {
            throw new ArgumentException(
                $"A force element must join two different particles; both ends are particle {first}.", name);
        }
    }

    /// <summary>
    /// Refuses a list of particles that names one twice, in O(n log n) on a sorted copy (a body or a fluid lists
    /// thousands: comparing every pair would cost millions of steps), naming the particle and both places.
    /// </summary>
    public static void NoDuplicateParticles(ReadOnlySpan<int> particles, string name)
    {
        if (particles.Length < 2)
        {
            return;
        }

        var sorted = particles.ToArray();
        Array.Sort(sorted);
        for (var k = 1; k < sorted.Length; k++)
        {
            if (sorted[k] == sorted[k - 1])
            {
                var listed = particles.ForReading();
                var particle = sorted[k];
                var first = 0;
                while (listed[first] != particle)
                {
                    first++;
                }

                var second = first + 1;
                while (listed[second] != particle)
                {
                    second++;
                }

                throw new ArgumentException($"Particle {particle} is listed twice (at {first} and {second}).", name);
            }
        }
    }

    public static void NotNull(object? value, string name)
    {
        if (value is null)
        {
            throw new ArgumentNullException(name);
        }
    }

    private static string Suffix(string? hint) => hint is null ? string.Empty : " " + hint;
}
