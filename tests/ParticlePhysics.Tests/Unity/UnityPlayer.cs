using System;
using System.Collections.Generic;
using System.IO;
using System.Reflection;
using System.Runtime.Loader;
using ParticlePhysics.Cloth;
using ParticlePhysics.Driver;

namespace ParticlePhysics.Tests.Unity;

/// <summary>
/// The compiled Unity sample running on the stand-in UnityEngine, in an assembly load context of its own (so that the
/// stand-in's static Time, Debug and frame loop belong to one test): a game object with a <c>SimulatedCloth</c>, the
/// Inspector values set by field name, frames run by the stand-in's frame loop. ParticlePhysics itself is the test's own,
/// so the sample's cloth and driver are the types the test sees.
/// </summary>
internal sealed class UnityPlayer : IDisposable
{
    private readonly AssemblyLoadContext _context;
    private readonly Action<float> _runFrame;
    private readonly Type _debug;

    public UnityPlayer(Action<object>? configure = null, string sample = "SimulatedCloth", byte[]? scriptImage = null)
    {
        _context = new StandInContext();
        var unityEngine = _context.LoadFromStream(new MemoryStream(UnityScripts.StandInImage));
        var scripts = _context.LoadFromStream(new MemoryStream(scriptImage ?? UnityScripts.SampleImage));
        var playerLoop = unityEngine.GetType("UnityEngine.StandIn.PlayerLoop", throwOnError: true)!;
        _runFrame = playerLoop.GetMethod("RunFrame")!.CreateDelegate<Action<float>>();
        _debug = unityEngine.GetType("UnityEngine.Debug", throwOnError: true)!;

        SampleType = scripts.GetType(sample, throwOnError: true)!;
        var gameObjectType = unityEngine.GetType("UnityEngine.GameObject", throwOnError: true)!;
        GameObject = Activator.CreateInstance(gameObjectType, "Cloth")!;
        Sample = gameObjectType.GetMethod("AddComponent")!.MakeGenericMethod(SampleType).Invoke(GameObject, null)!;
        configure?.Invoke(Sample);
    }

    public Type SampleType { get; }

    public object GameObject { get; }

    /// <summary>The SimulatedCloth component.</summary>
    public object Sample { get; }

    /// <summary>The sample's cloth (after the first frame, which runs Start).</summary>
    public ParticleCloth Cloth => (ParticleCloth)SampleType.GetProperty("Simulation")!.GetValue(Sample)!;

    /// <summary>The sample's driver (after the first frame).</summary>
    public FixedTimestepDriver Driver => (FixedTimestepDriver)SampleType.GetProperty("Driver")!.GetValue(Sample)!;

    /// <summary>The component's enabled flag (the sample clears it when the simulation diverges).</summary>
    public bool Enabled => (bool)SampleType.GetProperty("enabled")!.GetValue(Sample)!;

    /// <summary>The errors the sample logged through Debug.LogError.</summary>
    public string Errors => string.Join("\n", (IReadOnlyList<string>)_debug.GetProperty("Errors")!.GetValue(null)!);

    /// <summary>The stand-in Mesh the sample gave its MeshFilter.</summary>
    public object Mesh
    {
        get
        {
            var filterType = GameObject.GetType().Assembly.GetType("UnityEngine.MeshFilter", throwOnError: true)!;
            var filter = GameObject.GetType().GetMethod("GetComponent")!.MakeGenericMethod(filterType).Invoke(GameObject, null)!;
            return filterType.GetProperty("sharedMesh")!.GetValue(filter)!;
        }
    }

    /// <summary>One frame of the stand-in's loop: Start on the first, then Update. Allocates nothing itself.</summary>
    public void RunFrame(float deltaTime) => _runFrame(deltaTime);

    public void SetField(string name, object value) => SampleType.GetField(name)!.SetValue(Sample, value);

    public object GetField(string name) => SampleType.GetField(name)!.GetValue(Sample)!;

    public object Call(string method, params object[] arguments) => SampleType.GetMethod(method)!.Invoke(Sample, arguments)!;

    /// <summary>A property of the stand-in mesh (vertices, normals, triangles: copies, as in Unity).</summary>
    public T MeshProperty<T>(string name) => (T)Mesh.GetType().GetProperty(name)!.GetValue(Mesh)!;

    public void Dispose() => _context.Unload();

    private sealed class StandInContext : AssemblyLoadContext
    {
        public StandInContext()
            : base(isCollectible: true)
        {
        }

        // UnityEngine and Assembly-CSharp are loaded into this context from their images; everything else (netstandard,
        // ParticlePhysics) comes from the default context.
        protected override Assembly? Load(AssemblyName assemblyName)
        {
            foreach (var loaded in Assemblies)
            {
                if (AssemblyName.ReferenceMatchesDefinition(assemblyName, loaded.GetName()))
                {
                    return loaded;
                }
            }

            return null;
        }
    }
}
