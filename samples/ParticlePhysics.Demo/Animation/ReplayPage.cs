using System;
using System.Collections.Generic;
using System.IO;
using System.IO.Compression;
using System.Reflection;
using System.Text;
using System.Text.Json;
using ParticlePhysics.Demo.Output;
using ParticlePhysics.Demo.Running;

namespace ParticlePhysics.Demo.Animation;

/// <summary>
/// Writes a replay as one self-contained HTML page: the template <c>replay.html</c> (an embedded resource: the
/// styles, the controls and a canvas-2D renderer) with the scene and the frames filled in. It loads nothing
/// from the network. The frames are float32 positions stored losslessly and compactly: each coordinate's 32 bits
/// minus the same coordinate's bits in the previous frame (small numbers while the motion is smooth), split into
/// four byte planes, zlib-compressed, base64 (see <see cref="EncodeFrames"/>).
/// </summary>
internal static class ReplayPage
{
    private const string TemplateName = "ParticlePhysics.Demo.Animation.replay.html";
    private const string TitleMark = "{{TITLE}}";
    private const string DataMark = "{{DATA}}";
    private const string FramesMark = "{{FRAMES}}";

    /// <summary>The page's template, as embedded in the demo.</summary>
    public static string Template()
    {
        using var stream = Assembly.GetExecutingAssembly().GetManifestResourceStream(TemplateName)
            ?? throw new InvalidOperationException($"the demo lacks its embedded resource {TemplateName}.");
        using var reader = new StreamReader(stream, Encoding.UTF8);
        return reader.ReadToEnd();
    }

    /// <summary>Writes the page of a recorded run.</summary>
    /// <param name="output">Receives the page (UTF-8).</param>
    /// <param name="scene">What does not move: pins, links, anchors, surface, colliders, radii.</param>
    /// <param name="recorder">The frames, after the run has finished.</param>
    /// <param name="title">The run in a few words (scenario, integrator, dt).</param>
    /// <param name="subtitle">The parameters.</param>
    /// <param name="summary">How the run ended (the table format's summary line).</param>
    public static void Write(Stream output, ReplayScene scene, ReplayRecorder recorder, string title, string subtitle, string summary)
    {
        var template = Template();
        var titleAt = template.IndexOf(TitleMark, StringComparison.Ordinal);
        var dataAt = template.IndexOf(DataMark, StringComparison.Ordinal);
        var framesAt = template.IndexOf(FramesMark, StringComparison.Ordinal);
        using var writer = new StreamWriter(output, new UTF8Encoding(false), 1 << 16, leaveOpen: true);
        writer.Write(template.AsSpan(0, titleAt));
        writer.Write(System.Net.WebUtility.HtmlEncode(title));
        writer.Write(template.AsSpan(titleAt + TitleMark.Length, dataAt - titleAt - TitleMark.Length));
        writer.Write(Data(scene, recorder, title, subtitle, summary));
        writer.Write(template.AsSpan(dataAt + DataMark.Length, framesAt - dataAt - DataMark.Length));
        writer.Write(Convert.ToBase64String(EncodeFrames(recorder.Positions, 3 * recorder.ParticleCount)));
        writer.Write(template.AsSpan(framesAt + FramesMark.Length));
    }

    /// <summary>
    /// The frames as stored in the page: for coordinate i, its float32 bits d_i = b_i - b_(i - stride) (mod 2^32,
    /// b_i itself in the first frame), written as four planes (all the low bytes, then the next ones, ...) and
    /// zlib-compressed. The page adds the differences back, so the positions are exactly the float32 values.
    /// </summary>
    public static byte[] EncodeFrames(IReadOnlyList<float> positions, int stride)
    {
        var count = positions.Count;
        var planes = new byte[4 * count];
        uint previous(int i) => i >= stride ? (uint)BitConverter.SingleToInt32Bits(positions[i - stride]) : 0u;
        for (var i = 0; i < count; i++)
        {
            var delta = unchecked((uint)BitConverter.SingleToInt32Bits(positions[i]) - previous(i));
            planes[i] = (byte)delta;
            planes[count + i] = (byte)(delta >> 8);
            planes[(2 * count) + i] = (byte)(delta >> 16);
            planes[(3 * count) + i] = (byte)(delta >> 24);
        }

        using var packed = new MemoryStream();
        using (var zlib = new ZLibStream(packed, CompressionLevel.Optimal, leaveOpen: true))
        {
            zlib.Write(planes);
        }

        return packed.ToArray();
    }

    /// <summary>The inverse of <see cref="EncodeFrames"/>, as the page computes it (for tests).</summary>
    public static float[] DecodeFrames(byte[] encoded, int stride)
    {
        using var zlib = new ZLibStream(new MemoryStream(encoded), CompressionMode.Decompress);
        using var planes = new MemoryStream();
        zlib.CopyTo(planes);
        var bytes = planes.ToArray();
        var count = bytes.Length / 4;
        var words = new uint[count];
        for (var i = 0; i < count; i++)
        {
            var delta = bytes[i] | ((uint)bytes[count + i] << 8) | ((uint)bytes[(2 * count) + i] << 16) | ((uint)bytes[(3 * count) + i] << 24);
            words[i] = unchecked(delta + (i >= stride ? words[i - stride] : 0u));
        }

        return Array.ConvertAll(words, w => BitConverter.Int32BitsToSingle(unchecked((int)w)));
    }

    private static string Data(ReplayScene scene, ReplayRecorder recorder, string title, string subtitle, string summary)
    {
        using var buffer = new MemoryStream();
        using (var json = new Utf8JsonWriter(buffer))
        {
            var outcome = recorder.Outcome;
            json.WriteStartObject();
            json.WriteNumber("version", 1);
            json.WriteString("title", title);
            json.WriteString("subtitle", subtitle);
            json.WriteString("summary", summary);
            json.WriteString("status", outcome?.Diverged is not null ? "diverged" : outcome?.Interrupted == true ? "interrupted" : "completed");
            json.WriteNumber("particles", scene.ParticleCount);
            if (Array.Exists(scene.Radii, r => r > 0))
            {
                WriteNumbers(json, "radii", scene.Radii);
            }

            json.WriteStartArray("pinned");
            foreach (var i in scene.Pinned)
            {
                json.WriteNumberValue(i);
            }

            json.WriteEndArray();
            json.WriteStartArray("anchors");
            foreach (var a in scene.Anchors)
            {
                WriteVector(json, null, a);
            }

            json.WriteEndArray();
            WriteLinks(json, scene);
            json.WriteStartArray("triangles");
            foreach (var i in scene.Triangles)
            {
                json.WriteNumberValue(i);
            }

            json.WriteEndArray();
            json.WriteStartArray("loads");
            foreach (var (particle, force) in scene.Loads)
            {
                json.WriteStartArray();
                json.WriteNumberValue(particle);
                WriteNumberValue(json, force.X);
                WriteNumberValue(json, force.Y);
                WriteNumberValue(json, force.Z);
                json.WriteEndArray();
            }

            json.WriteEndArray();
            json.WriteStartArray("colliders");
            foreach (var c in scene.Colliders)
            {
                WriteCollider(json, c);
            }

            json.WriteEndArray();
            WriteNumbers(json, "times", recorder.Times);
            json.WriteStartArray("valueNames");
            foreach (var name in recorder.ValueNames)
            {
                json.WriteStringValue(name);
            }

            json.WriteEndArray();
            json.WriteStartArray("values");
            foreach (var v in recorder.Values)
            {
                // Shown to people only: six significant digits, as in the table format.
                if (double.IsFinite(v))
                {
                    json.WriteRawValue(Numbers.Brief(v));
                }
                else
                {
                    json.WriteNullValue();
                }
            }

            json.WriteEndArray();
            if (recorder.StageTimes is { } stageTimes)
            {
                // --profile: each stage's mean time per step (seconds) since the frame before, frame after frame.
                json.WriteStartObject("profile");
                json.WriteStartArray("stages");
                foreach (var name in ReplayRecorder.StageNames)
                {
                    json.WriteStringValue(name);
                }

                json.WriteEndArray();
                json.WriteStartArray("seconds");
                foreach (var seconds in stageTimes)
                {
                    json.WriteRawValue(Numbers.Brief(Math.Max(0.0, seconds)));
                }

                json.WriteEndArray();
                json.WriteEndObject();
            }

            json.WriteString("frames", "float32 bits minus the previous frame's, 4 byte planes, zlib, base64");
            json.WriteEndObject();
        }

        return Encoding.UTF8.GetString(buffer.ToArray());
    }

    private static void WriteLinks(Utf8JsonWriter json, ReplayScene scene)
    {
        json.WriteStartObject("links");
        foreach (var kind in new[] { LinkKind.Spring, LinkKind.Rod, LinkKind.Cable })
        {
            var ends = new List<int>();
            var lengths = new List<double>();
            foreach (var link in scene.Links)
            {
                if (link.Kind == kind)
                {
                    ends.Add(link.First);
                    ends.Add(link.Second);
                    lengths.Add(link.Length);
                }
            }

            if (ends.Count == 0)
            {
                continue;
            }

            var name = kind.ToString().ToLowerInvariant();
            json.WriteStartArray(name);
            foreach (var end in ends)
            {
                json.WriteNumberValue(end);
            }

            json.WriteEndArray();
            if (kind == LinkKind.Cable)
            {
                WriteNumbers(json, name + "Lengths", lengths);
            }
        }

        json.WriteEndObject();
    }

    // The core's ObstacleShape as it reads (a plane's normal is its AxisY), at t = 0, and the velocity it moves at.
    private static void WriteCollider(Utf8JsonWriter json, ReplayCollider collider)
    {
        var c = collider.Shape;
        json.WriteStartObject();
        json.WriteString("kind", c.Kind.ToString().ToLowerInvariant());
        WriteVector(json, "center", c.Center);
        WriteNumber(json, "radius", c.Radius);
        WriteVector(json, "halfExtents", c.HalfExtents);
        json.WriteStartArray("axes");
        WriteVector(json, null, c.AxisX);
        WriteVector(json, null, c.AxisY);
        WriteVector(json, null, c.AxisZ);
        json.WriteEndArray();
        if (collider.Velocity != Vector3d.Zero)
        {
            WriteVector(json, "velocity", collider.Velocity);
        }

        json.WriteEndObject();
    }

    private static void WriteVector(Utf8JsonWriter json, string? name, Vector3d v)
    {
        if (name is null)
        {
            json.WriteStartArray();
        }
        else
        {
            json.WriteStartArray(name);
        }

        WriteNumberValue(json, v.X);
        WriteNumberValue(json, v.Y);
        WriteNumberValue(json, v.Z);
        json.WriteEndArray();
    }

    private static void WriteNumbers(Utf8JsonWriter json, string name, IReadOnlyList<double> values)
    {
        json.WriteStartArray(name);
        foreach (var v in values)
        {
            WriteNumberValue(json, v);
        }

        json.WriteEndArray();
    }

    private static void WriteNumber(Utf8JsonWriter json, string name, double value)
    {
        json.WritePropertyName(name);
        WriteNumberValue(json, value);
    }

    // JSON has no NaN or infinity: such values become null, as in the json format.
    private static void WriteNumberValue(Utf8JsonWriter json, double value)
    {
        if (double.IsFinite(value))
        {
            json.WriteRawValue(Numbers.RoundTrip(value));
        }
        else
        {
            json.WriteNullValue();
        }
    }
}
