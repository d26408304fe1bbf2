namespace ParticlePhysics;

/// <summary>
/// An integrator whose step is one kick and one drift over the whole interval: v1 = v0 + dt a(t, x0, v0), then
/// x1 = x0 + dt v1 (semi-implicit Euler). The world tells the constraint sets so
/// (<see cref="ConstraintContext.KickDrift"/>): a set may then fold a correction dx of the end positions into the kick,
/// v1 += dx / dt, so that the end state is still a kick and a drift. The rods do, along their gradients at the step's
/// start, which makes the step the constrained symplectic Euler method (SHAKE): its energy stays bounded, where a
/// projection of the positions alone let the explicit tension gain energy without bound.
/// </summary>
public interface IKickDriftIntegrator : IIntegrator
{
}
