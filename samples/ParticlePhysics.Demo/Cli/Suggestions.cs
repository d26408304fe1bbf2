using System;
using System.Collections.Generic;
using System.Linq;

namespace ParticlePhysics.Demo.Cli;

/// <summary>"Did you mean ...?" for a misspelled name: the closest candidate by edit distance, if it is close.</summary>
internal static class Suggestions
{
    /// <summary>" (did you mean 'rk4'?)" or an empty string when nothing is close.</summary>
    public static string DidYouMean(string? typed, IEnumerable<string> candidates)
    {
        if (string.IsNullOrEmpty(typed))
        {
            return string.Empty;
        }

        var best = candidates
            .Select(c => (Name: c, Distance: Distance(typed, c)))
            .OrderBy(c => c.Distance)
            .FirstOrDefault();
        var close = best.Name is not null
            && (best.Distance <= Math.Max(2, typed.Length / 3) || best.Name.StartsWith(typed, StringComparison.Ordinal));
        return close ? $" (did you mean '{best.Name}'?)" : string.Empty;
    }

    /// <summary>The Levenshtein distance between two strings.</summary>
    public static int Distance(string a, string b)
    {
        var previous = new int[b.Length + 1];
        var current = new int[b.Length + 1];
        for (var j = 0; j <= b.Length; j++)
        {
            previous[j] = j;
        }

        for (var i = 1; i <= a.Length; i++)
        {
            current[0] = i;
            for (var j = 1; j <= b.Length; j++)
            {
                var substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
                current[j] = Math.Min(substitution, Math.Min(previous[j], current[j - 1]) + 1);
            }

            (previous, current) = (current, previous);
        }

        return previous[b.Length];
    }
}
