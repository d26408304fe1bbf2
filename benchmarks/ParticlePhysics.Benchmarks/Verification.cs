using System;
using System.Globalization;
using ParticlePhysics.Benchmarks.Student;
using ParticlePhysics.Integrators;
using MathNetVector = MathNet.Numerics.LinearAlgebra.Vector<double>;

namespace ParticlePhysics.Benchmarks;

/// <summary>
/// The verify mode: the comparisons are apples to apples only if the three codes compute the same cloth. After
/// <see cref="ClothFixture.StepsPerInvoke"/> RK4 steps from rest at dt = 1 ms (n = 16 and 32):
/// the student's single-precision cloth must match the library's positions within <see cref="StudentTolerance"/>
/// (float rounding), Math.NET's RK4 within <see cref="MathNetTolerance"/> (only the summation order differs);
/// and a library step must allocate nothing. Also prints a checksum the C reference prints too.
/// xpbd: one simulated second of the library and of the C reference (<see cref="NativeXpbd"/>, which needs gcc) must be
/// bit-identical at n = 16, 32 and 64.
/// </summary>
internal static class Verification
{
    public const double StudentTolerance = 1e-5;
    public const double MathNetTolerance = 1e-12;

    public static int Run()
    {
        var ok = true;
        foreach (var n in new[] { 16, 32 })
        {
            var cloth = new ClothFixture(n);
            var rk4 = new RungeKutta4();
            for (var s = 0; s < ClothFixture.StepsPerInvoke; s++)
            {
                cloth.System.Step(rk4, cloth.TimeStep);
            }

            var library = cloth.System.State.ToArray();
            var fall = -library[(3 * cloth.ParticleCount) - 2];
            var freeFall = 0.5 * 9.81 * Math.Pow(ClothFixture.StepsPerInvoke * cloth.TimeStep, 2);
            ok &= Check($"n = {n}: the far corner has fallen, but no faster than free fall [m]", fall, 0.5 * freeFall, 1.001 * freeFall);

            var student = new StudentCloth(n);
            for (var s = 0; s < ClothFixture.StepsPerInvoke; s++)
            {
                student.StepRk4((float)cloth.TimeStep);
            }

            var studentError = 0.0;
            for (var i = 0; i < cloth.ParticleCount; i++)
            {
                var p = student.Particles[i].Position;
                studentError = Math.Max(studentError, Math.Abs(p.X - library[3 * i]));
                studentError = Math.Max(studentError, Math.Abs(p.Y - library[(3 * i) + 1]));
                studentError = Math.Max(studentError, Math.Abs(p.Z - library[(3 * i) + 2]));
            }

            ok &= Check($"n = {n}: student baseline vs library, max position difference [m]", studentError, 0, StudentTolerance);

            var fresh = new ClothFixture(n);
            var peer = new MathNetPeer(fresh.System);
            var mathNet = peer.Solve(
                MathNetVector.Build.DenseOfArray(fresh.InitialState.ToArray()), fresh.TimeStep, ClothFixture.StepsPerInvoke);
            var mathNetError = 0.0;
            for (var i = 0; i < library.Length; i++)
            {
                mathNetError = Math.Max(mathNetError, Math.Abs(mathNet[i] - library[i]));
            }

            ok &= Check($"n = {n}: Math.NET RK4 vs library, max state difference", mathNetError, 0, MathNetTolerance);

            var checksum = 0.0;
            for (var i = 0; i < library.Length; i++)
            {
                checksum += library[i];
            }

            Console.WriteLine(string.Create(
                CultureInfo.InvariantCulture,
                $"n = {n}: checksum (sum of the state after {ClothFixture.StepsPerInvoke} steps) = {checksum:R}"));
        }

        foreach (var n in new[] { 16, 32, 64 })
        {
            // The C xpbd reference (built with gcc if needed) must give the same state to the last bit after the same
            // second; the checksum is the one cloth_xpbd --run 60 n prints.
            var xpbd = new XpbdCloth(n);
            xpbd.SimulateSecond();
            Console.WriteLine(string.Create(
                CultureInfo.InvariantCulture,
                $"n = {n}: xpbd checksum (sum of the state after {XpbdCloth.StepsPerSecond} steps of 1/60 s, {XpbdCloth.Substeps} substeps) = {xpbd.Checksum():R}"));
            using var c = new NativeXpbd(n);
            c.Run(XpbdCloth.FrameTime, XpbdCloth.Substeps, XpbdCloth.StepsPerSecond);
            ok &= Check($"n = {n}: C xpbd reference vs library after one second, differing state values", Differences(c.State(n * n), xpbd.System.State), 0, 0);
        }

        var allocation = new ClothFixture(32);
        var method = new RungeKutta4();
        allocation.System.Step(method, allocation.TimeStep);
        var before = GC.GetAllocatedBytesForCurrentThread();
        for (var s = 0; s < 100; s++)
        {
            allocation.System.Step(method, allocation.TimeStep);
        }

        var bytesPerStep = (GC.GetAllocatedBytesForCurrentThread() - before) / 100.0;
        ok &= Check("n = 32: bytes allocated per library RK4 step", bytesPerStep, 0, 0);

        Console.WriteLine(ok ? "verify: all checks passed" : "verify: FAILED");
        return ok ? 0 : 1;
    }

    private static int Differences(ReadOnlySpan<double> expected, ReadOnlySpan<double> actual)
    {
        var count = 0;
        for (var i = 0; i < expected.Length; i++)
        {
            count += BitConverter.DoubleToInt64Bits(expected[i]) == BitConverter.DoubleToInt64Bits(actual[i]) ? 0 : 1;
        }

        return count;
    }

    private static bool Check(string what, double value, double low, double high)
    {
        var pass = value >= low && value <= high;
        Console.WriteLine(string.Create(
            CultureInfo.InvariantCulture, $"{(pass ? "ok  " : "FAIL")} {what}: {value:G4} (allowed {low:G3} to {high:G3})"));
        return pass;
    }
}
