using System;
using System.Globalization;

namespace ParticlePhysics.Forces;

/// <summary>
/// What a force's last <see cref="IForceJacobian.Linearize"/> covered: how many elements of each kind it had then.
/// A product asked before any linearisation, or after elements were added since, would read a linearisation that does
/// not describe them (past the end of its arrays, for the spring network's pointer loop): <see cref="Check"/> throws
/// instead.
/// </summary>
internal struct LinearizationStamp
{
    // Element counts plus one, so that the default value (0) means "never linearised".
    private int _first;
    private int _second;

    /// <summary>Notes that a linearisation now covers <paramref name="first"/> and <paramref name="second"/> elements.</summary>
    public void Record(int first, int second)
    {
        _first = first + 1;
        _second = second + 1;
    }

    /// <summary>Throws unless the last linearisation covered exactly the elements there are now.</summary>
    /// <param name="owner">The force's type name, for the message.</param>
    /// <param name="first">The number of elements of the first kind now (pairs).</param>
    /// <param name="second">The number of elements of the second kind now (anchored), or 0.</param>
    public readonly void Check(string owner, int first, int second)
    {
        if (_first == first + 1 && _second == second + 1)
        {
            return;
        }

        throw new InvalidOperationException(_first == 0
            ? $"{owner}: a Jacobian product or diagonal block was asked for before any Linearize; call Linearize first."
            : string.Format(
                CultureInfo.InvariantCulture,
                "{0} was linearised with {1} + {2} elements but now has {3} + {4}: call Linearize again after adding elements.",
                owner,
                _first - 1,
                _second - 1,
                first,
                second));
    }
}
