namespace ParticlePhysics.Demo;

/// <summary>The demo's exit codes, as the contract fixes them.</summary>
internal static class ExitCodes
{
    /// <summary>The run completed.</summary>
    public const int Success = 0;

    /// <summary>A bad command line: one "error:" line on stderr.</summary>
    public const int Usage = 2;

    /// <summary>The simulation diverged: the rows already printed stay, one "error:" line on stderr.</summary>
    public const int Diverged = 3;

    /// <summary>Ctrl-C stopped the run: the rows already printed stay (128 + SIGINT, as shells report it).</summary>
    public const int Interrupted = 130;
}
