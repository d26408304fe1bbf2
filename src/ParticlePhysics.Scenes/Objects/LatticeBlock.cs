using System;
using ParticlePhysics.Bodies;
using ParticlePhysics.Constraints;
using ParticlePhysics.Scenes.Kinds;

namespace ParticlePhysics.Scenes.Objects;

/// <summary>
/// The block that a <c>granular</c> or a <c>fluid</c> object fills: <c>box</c> {"min", "max"} filled as a rigid box is
/// (<see cref="BodyLattice.Box"/>, cell centres at min + (i + 1/2) h, x fastest) at <c>spacing</c> h, each particle of
/// mass <c>density</c> h^3 (kg/m^3, default 1000).
/// </summary>
internal readonly struct LatticeBlock
{
    public const double DefaultDensity = 1000.0;

    private LatticeBlock(Vector3d[] positions, double spacing, double density)
    {
        Positions = positions;
        Spacing = spacing;
        Density = density;
        Mass = density * spacing * spacing * spacing;
    }

    /// <summary>The particles' positions, in the box rule's order.</summary>
    public Vector3d[] Positions { get; }

    /// <summary>The spacing h, m.</summary>
    public double Spacing { get; }

    /// <summary>The density, kg/m^3.</summary>
    public double Density { get; }

    /// <summary>Each particle's mass, density h^3, kg.</summary>
    public double Mass { get; }

    /// <summary>
    /// Reads <c>box</c>, <c>spacing</c> and <c>density</c> of a <paramref name="kind"/> object whose particles are
    /// called <paramref name="noun"/> in its errors; refuses a block too fine for a scene before its array is made.
    /// </summary>
    public static LatticeBlock Read(ObjectReader reader, string kind, string noun)
    {
        var box = reader.Object("box", $"a {kind} block's box")
            ?? throw reader.ObjectError($"a {kind} object needs \"box\": {{\"min\": [x, y, z], \"max\": [x, y, z]}} in m, the block its {noun}s fill");
        var min = box.Vector("min", null, "m");
        var max = box.Vector("max", null, "m");
        if (!(max.X > min.X && max.Y > min.Y && max.Z > min.Z))
        {
            throw box.Error(box.Get("max")!.Value, box.PathOf("max"), FormattableString.Invariant($"must be above \"min\" {Show(min)} along every axis: the block's far corner"));
        }

        box.Finish();
        var spacing = reader.Number("spacing", null, ValueRule.Positive, "m");
        var count = CountOf(max.X - min.X, spacing) * CountOf(max.Y - min.Y, spacing) * CountOf(max.Z - min.Z, spacing);
        if (count > ParticleWorld.MaxParticles)
        {
            throw reader.ObjectError(FormattableString.Invariant($"fills with {count:N0} {noun}s; a scene holds at most {ParticleWorld.MaxParticles:N0}"));
        }

        var density = reader.Number("density", DefaultDensity, ValueRule.Positive, "kg/m^3");
        var mass = density * spacing * spacing * spacing;
        if (!(mass > 0) || double.IsInfinity(mass) || double.IsInfinity(1.0 / mass))
        {
            throw reader.Error(reader.Get("density")!.Value, reader.PathOf("density"), FormattableString.Invariant($"gives each {noun} a mass {mass:G6} kg (density h^3) whose inverse is not finite"));
        }

        return new LatticeBlock(BodyLattice.Box(0.5 * (min + max), max - min, Rotation3d.Identity, spacing), spacing, density);
    }

    // The box rule's count along one side (BodyLattice.Box): round(side / h), at least 1.
    private static double CountOf(double side, double spacing) => Math.Max(1.0, Math.Round(side / spacing));

    private static string Show(Vector3d v) => FormattableString.Invariant($"[{v.X:G6}, {v.Y:G6}, {v.Z:G6}]");
}
