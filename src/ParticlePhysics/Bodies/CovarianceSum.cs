namespace ParticlePhysics.Bodies;

/// <summary>
/// The sum A_pq = sum_i m_i p_i q_i^T of a cluster (p its current offsets, q its rest offsets), gathered one particle at
/// a time inside a pass that also sums other things, and the rotation of its polar decomposition.
/// </summary>
internal struct CovarianceSum
{
    private double _a00, _a01, _a02, _a10, _a11, _a12, _a20, _a21, _a22;

    /// <summary>Adds p q^T, with <paramref name="p"/> already weighted by the particle's mass.</summary>
    public void Add(Vector3d p, Vector3d q)
    {
        _a00 += p.X * q.X;
        _a01 += p.X * q.Y;
        _a02 += p.X * q.Z;
        _a10 += p.Y * q.X;
        _a11 += p.Y * q.Y;
        _a12 += p.Y * q.Z;
        _a20 += p.Z * q.X;
        _a21 += p.Z * q.Y;
        _a22 += p.Z * q.Z;
    }

    /// <summary>The rotation of A's polar decomposition, from <paramref name="start"/> (<see cref="RotationExtraction"/>).</summary>
    public readonly Quaternion4d Rotation(Quaternion4d start) =>
        RotationExtraction.Extract(_a00, _a01, _a02, _a10, _a11, _a12, _a20, _a21, _a22, start);
}
