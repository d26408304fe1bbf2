using System;

namespace ParticlePhysics.Demo.Running;

/// <summary>A column a particle scenario adds after the common ones: its name and how a row's value is read.</summary>
internal sealed record ExtraColumn(string Name, Func<ParticleSimulation, double> Value);
