using System;

namespace ParticlePhysics.Demo;

/// <summary>A bad command line: the program prints "error: " and the message on one line and exits with code 2.</summary>
internal sealed class UsageException : Exception
{
    public UsageException(string message)
        : base(message)
    {
    }

    public UsageException()
    {
    }

    public UsageException(string message, Exception innerException)
        : base(message, innerException)
    {
    }
}
