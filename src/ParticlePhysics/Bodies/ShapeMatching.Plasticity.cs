using System;
using ParticlePhysics.Numerics;

namespace ParticlePhysics.Bodies;

// Soft bodies' plasticity: a particle pulled farther than the yield from its goal moves its rest offset towards where
// it is, by the creep fraction of the excess (FleX's per-particle threshold and creep).
public sealed partial class ShapeMatching
{
    private double[] _yield = Array.Empty<double>(); // per body, m; infinite: elastic
    private double[] _creep = Array.Empty<double>();
    private Vector3d[] _savedRest = Array.Empty<Vector3d>();
    private bool _anyPlastic;

    /// <summary>
    /// Makes soft body <paramref name="body"/> plastic: at each projection, a particle whose distance d from its goal is
    /// above <paramref name="yield"/> moves its rest offset a fraction <paramref name="creep"/> of the excess d - yield
    /// towards where it is (in the body's frame), so that a dent deeper than the yield stays. The rest shape
    /// (<see cref="RestShapeOf"/>) is then state: a failed step restores it. Only between steps.
    /// </summary>
    /// <param name="body">A soft body.</param>
    /// <param name="yield">The distance from the goal, m, beyond which the body deforms for good: a positive number.</param>
    /// <param name="creep">The fraction of the excess taken into the rest shape per projection, in (0, 1].</param>
    /// <exception cref="ArgumentException">The body is rigid.</exception>
    /// <exception cref="ArgumentOutOfRangeException">A yield not positive and finite, or a creep outside (0, 1].</exception>
    public void SetPlasticity(int body, double yield, double creep)
    {
        _world.ThrowIfStepping();
        CheckBody(body);
        if (_rigid[body])
        {
            throw new ArgumentException($"Body {body} is rigid: only a soft body can be plastic.", nameof(body));
        }

        if (!(yield > 0.0) || double.IsInfinity(yield))
        {
            throw new ArgumentOutOfRangeException(nameof(yield), yield, $"yield must be a positive distance in m; got {Guard.Format(yield)}.");
        }

        if (!(creep > 0.0 && creep <= 1.0))
        {
            throw new ArgumentOutOfRangeException(nameof(creep), creep, $"creep must be in (0, 1]; got {Guard.Format(creep)}.");
        }

        if (_yield.Length < _stiffness.Length)
        {
            var old = _yield.Length;
            Array.Resize(ref _yield, _stiffness.Length);
            Array.Resize(ref _creep, _stiffness.Length);
            _yield.AsSpan(old).Fill(double.PositiveInfinity);
        }

        if (_savedRest.Length < _rest.Length)
        {
            _savedRest = new Vector3d[_rest.Length];
        }

        _yield[body] = yield;
        _creep[body] = creep;
        _anyPlastic = true;
        _revision++;
    }

    /// <summary>Body <paramref name="body"/>'s yield, m (infinite for a body that is not plastic), and creep.</summary>
    public (double Yield, double Creep) GetPlasticity(int body)
    {
        CheckBody(body);
        return body < _yield.Length && !double.IsInfinity(_yield[body]) ? (_yield[body], _creep[body]) : (double.PositiveInfinity, 0.0);
    }

    private bool IsPlastic(int body) => _anyPlastic && body < _yield.Length && !double.IsInfinity(_yield[body]);

    // The entry k's rest offset after its particle at xi, a distance |xi - goal| from its goal: d = |xi - goal| beyond
    // the yield moves the offset by creep (d - yield) / d of (xi - goal), taken into the body's frame by q^-1.
    private void Yield(int body, int k, Vector3d xi, Vector3d goal, Quaternion4d q)
    {
        var away = xi - goal;
        var d = away.Length;
        var excess = d - _yield[body];
        if (excess > 0.0)
        {
            _rest[k] += (_creep[body] * excess / d) * q.RotateInverse(away);
        }
    }

    private void SaveRestShapes()
    {
        if (_anyPlastic)
        {
            Array.Copy(_rest, _savedRest, _entries);
        }
    }

    private void RestoreRestShapes()
    {
        if (_anyPlastic)
        {
            Array.Copy(_savedRest, _rest, _entries);
        }
    }
}
