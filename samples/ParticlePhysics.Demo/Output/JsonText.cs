using System.Text.Json;

namespace ParticlePhysics.Demo.Output;

/// <summary>JSON string literals, escaped by System.Text.Json.</summary>
internal static class JsonText
{
    public static string String(string value) => JsonSerializer.Serialize(value);

    public static string Value(object value) => value switch
    {
        double d => Numbers.Json(d),
        int i => Numbers.Json(i),
        _ => String(value.ToString() ?? string.Empty),
    };
}
