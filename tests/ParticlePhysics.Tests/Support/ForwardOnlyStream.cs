using System;
using System.IO;

namespace ParticlePhysics.Tests.Support;

/// <summary>A stream that cannot seek and returns at most 7 bytes per read, like a network stream.</summary>
internal sealed class ForwardOnlyStream : Stream
{
    private readonly byte[] _bytes;
    private readonly int _length;
    private int _position;

    public ForwardOnlyStream(byte[] bytes, int length)
    {
        _bytes = bytes;
        _length = length;
    }

    public override bool CanRead => true;

    public override bool CanSeek => false;

    public override bool CanWrite => false;

    public override long Length => throw new NotSupportedException();

    public override long Position { get => throw new NotSupportedException(); set => throw new NotSupportedException(); }

    public override int Read(byte[] buffer, int offset, int count)
    {
        var n = Math.Min(Math.Min(count, 7), _length - _position);
        Array.Copy(_bytes, _position, buffer, offset, n);
        _position += n;
        return n;
    }

    public override void Flush()
    {
    }

    public override long Seek(long offset, SeekOrigin origin) => throw new NotSupportedException();

    public override void SetLength(long value) => throw new NotSupportedException();

    public override void Write(byte[] buffer, int offset, int count) => throw new NotSupportedException();
}
