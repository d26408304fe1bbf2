using System;
using ParticlePhysics.Bodies;
using Xunit;

namespace ParticlePhysics.Tests.Bodies;

public class RotationExtractionTests
{
    [Theory]
    [InlineData(0.3, 1.0, 2.0, 3.0, 1.2)]
    [InlineData(2.9, -1.0, 0.5, 0.2, 0.4)]
    [InlineData(1e-9, 0.0, 0.0, 1.0, 3.0)]
    public void The_rotation_of_a_turned_stretched_matrix_is_its_polar_factor(double angle, double ax, double ay, double az, double stretch)
    {
        // A = R S with S symmetric positive definite: the polar factor is R exactly (the oracle: R built directly).
        var axis = new Vector3d(ax, ay, az) / new Vector3d(ax, ay, az).Length;
        var r = new ParticlePhysics.Constraints.Rotation3d(axis.X * Math.Sin(angle / 2), axis.Y * Math.Sin(angle / 2), axis.Z * Math.Sin(angle / 2), Math.Cos(angle / 2));
        double[,] s = { { stretch, 0.2, -0.1 }, { 0.2, 1.5, 0.3 }, { -0.1, 0.3, 0.8 } };
        var a = new double[3, 3];
        for (var j = 0; j < 3; j++)
        {
            var column = r.Rotate(new Vector3d(s[0, j], s[1, j], s[2, j]));
            a[0, j] = column.X;
            a[1, j] = column.Y;
            a[2, j] = column.Z;
        }

        // A start within a quarter turn of the answer, as a warm start is.
        var start = Quaternion4d.FromRotationVector(0.6 * angle * axis + new Vector3d(0.1, -0.05, 0.02));
        var q = RotationExtraction.Extract(a[0, 0], a[0, 1], a[0, 2], a[1, 0], a[1, 1], a[1, 2], a[2, 0], a[2, 1], a[2, 2], start);
        var sign = Math.Sign(q.W * r.W + q.X * r.X + q.Y * r.Y + q.Z * r.Z);
        Assert.Equal(r.W, sign * q.W, 12);
        Assert.Equal(r.X, sign * q.X, 12);
        Assert.Equal(r.Y, sign * q.Y, 12);
        Assert.Equal(r.Z, sign * q.Z, 12);
    }

    [Fact]
    public void The_exponential_map_turns_by_the_vectors_length_about_it()
    {
        var q = Quaternion4d.FromRotationVector(new Vector3d(0, 0, Math.PI / 2));
        var turned = q.Rotate(new Vector3d(1, 0, 0));
        Assert.Equal(0.0, turned.X, 15);
        Assert.Equal(1.0, turned.Y, 15);
        var small = Quaternion4d.FromRotationVector(new Vector3d(1e-6, 0, 0));
        Assert.Equal(0.0, (small.W - Math.Cos(5e-7)) / 5e-7, 15);
        Assert.Equal(0.0, (small.X - Math.Sin(5e-7)) / 5e-7, 15);
    }
}
