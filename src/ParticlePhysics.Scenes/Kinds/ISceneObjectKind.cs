namespace ParticlePhysics.Scenes.Kinds;

/// <summary>
/// A kind of object of the <c>objects</c> list (<c>particles</c>, <c>springs</c>, ...): its <c>"type"</c> name and how
/// it reads its JSON object. A new kind is one class and one line in <see cref="SceneKinds.CreateDefault"/>.
/// </summary>
internal interface ISceneObjectKind
{
    /// <summary>The value of <c>"type"</c> that selects it.</summary>
    string Name { get; }

    /// <summary>
    /// Reads and checks the object (every key through <paramref name="reader"/>, which then refuses the keys it did
    /// not ask for); throws a <see cref="SceneException"/> naming the bad value.
    /// </summary>
    SceneObject Read(ObjectReader reader, SceneReadContext context);
}

/// <summary>A kind of collider of the <c>colliders</c> list (<c>plane</c>, <c>sphere</c>, ...).</summary>
internal interface IColliderKind
{
    /// <summary>The value of <c>"type"</c> that selects it.</summary>
    string Name { get; }

    /// <summary>Reads and checks the collider; throws a <see cref="SceneException"/> naming the bad value.</summary>
    SceneCollider Read(ObjectReader reader, SceneReadContext context);
}

/// <summary>What a kind may need besides its own object: where the scene file is, and how many particles come before.</summary>
internal sealed class SceneReadContext
{
    public SceneReadContext(string file, string directory, int firstParticle)
    {
        File = file;
        Directory = directory;
        FirstParticle = firstParticle;
    }

    /// <summary>The scene file as the user named it.</summary>
    public string File { get; }

    /// <summary>The folder that paths in the file (OBJ meshes) are relative to.</summary>
    public string Directory { get; }

    /// <summary>The global index of the object's first particle: the particles of the objects before it.</summary>
    public int FirstParticle { get; }
}
