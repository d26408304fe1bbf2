namespace ParticlePhysics.Scenes.Kinds;

/// <summary>
/// A kind the contract names whose issue has not landed: reading one is refused with one line saying which issue
/// brings it, never ignored. The issue that builds the kind replaces its registration line.
/// </summary>
internal sealed class NotBuiltYet : ISceneObjectKind, IColliderKind
{
    private NotBuiltYet(string name, string issue)
    {
        Name = name;
        Issue = issue;
    }

    public string Name { get; }

    /// <summary>An object kind that <paramref name="issue"/> brings.</summary>
    public static ISceneObjectKind Object(string name, string issue) => new NotBuiltYet(name, issue);

    /// <summary>A collider kind that <paramref name="issue"/> brings.</summary>
    public static IColliderKind Collider(string name, string issue) => new NotBuiltYet(name, issue);

    /// <summary>The issue that brings the kind, by its subject ("cloth from any mesh").</summary>
    public string Issue { get; }

    public SceneObject Read(ObjectReader reader, SceneReadContext context) => throw Refuse(reader);

    SceneCollider IColliderKind.Read(ObjectReader reader, SceneReadContext context) => throw Refuse(reader);

    private SceneException Refuse(ObjectReader reader) =>
        reader.Error(reader.Get("type")!.Value, reader.PathOf("type"), $"not built yet: {Name} arrives with the issue \"{Issue}\"; this version builds {SceneKinds.Default.BuiltList(reader.Path.StartsWith("colliders", System.StringComparison.Ordinal))}");
}
