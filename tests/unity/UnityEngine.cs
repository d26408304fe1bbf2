// A stand-in for UnityEngine: the members the Unity sample (samples/unity/Cloth/SimulatedCloth.cs) calls, with
// Unity's signatures and enough behaviour to run it (a mesh keeps what it is given, a frame loop calls Start and
// Update), and the names of the UnityEngine types that a library's public types could clash with under
// `using UnityEngine;` (CS0104). Unity is not installed here; see tests/unity/README.md.
//
// Written in C# 7.2, which Mono's mcs compiles as well as Roslyn: tests/mono compiles it into the runtime comparison
// program, and the xunit tests (tests/ParticlePhysics.Tests/Unity) compile it with Unity's settings.
using System;
using System.Collections.Generic;
using System.Reflection;
using System.Runtime.InteropServices;
using Unity.Collections;
using UnityEngine.Rendering;

namespace UnityEngine
{
    /// <summary>Unity's base of every asset and component: a name, and Destroy.</summary>
    public class Object
    {
        /// <summary>The object's name.</summary>
        public string name { get; set; }

        /// <summary>Marks an object destroyed (Unity frees it at the end of the frame).</summary>
        public static void Destroy(Object obj)
        {
            if (obj != null)
            {
                obj.IsDestroyed = true;
            }
        }

        internal bool IsDestroyed { get; set; }
    }

    /// <summary>A part of a game object.</summary>
    public class Component : Object
    {
        /// <summary>The game object this component is attached to.</summary>
        public GameObject gameObject { get; internal set; }

        /// <summary>The game object's transform.</summary>
        public Transform transform => gameObject.transform;

        /// <summary>The first component of type T on the same game object, or null.</summary>
        public T GetComponent<T>() => gameObject.GetComponent<T>();
    }

    /// <summary>A component that can be enabled and disabled.</summary>
    public class Behaviour : Component
    {
        /// <summary>Disabled behaviours get no Update.</summary>
        public bool enabled { get; set; } = true;
    }

    /// <summary>The base class of scripts; Unity calls their Start once and their Update every frame.</summary>
    public class MonoBehaviour : Behaviour
    {
    }

    /// <summary>An entity in a scene: a transform and components.</summary>
    public sealed class GameObject : Object
    {
        private readonly List<Component> _components = new List<Component>();

        /// <summary>A game object with a transform.</summary>
        public GameObject(string name = "GameObject")
        {
            this.name = name;
            transform = AddComponent<Transform>();
        }

        /// <summary>The game object's transform.</summary>
        public Transform transform { get; }

        /// <summary>
        /// Adds a component of type T, and first those its [RequireComponent] attributes name that are missing.
        /// </summary>
        public T AddComponent<T>()
            where T : Component
        {
            foreach (RequireComponent required in typeof(T).GetCustomAttributes(typeof(RequireComponent), true))
            {
                if (FindComponent(required.m_Type0) == null)
                {
                    var added = (Component)Activator.CreateInstance(required.m_Type0);
                    added.gameObject = this;
                    _components.Add(added);
                }
            }

            var component = (T)Activator.CreateInstance(typeof(T));
            component.gameObject = this;
            _components.Add(component);
            StandIn.PlayerLoop.Register(component);
            return component;
        }

        /// <summary>The first component of type T, or null.</summary>
        public T GetComponent<T>()
        {
            var found = FindComponent(typeof(T));
            return found == null ? default(T) : (T)(object)found;
        }

        internal IReadOnlyList<Component> Components => _components;

        private Component FindComponent(Type type)
        {
            foreach (var component in _components)
            {
                if (type.IsInstanceOfType(component))
                {
                    return component;
                }
            }

            return null;
        }
    }

    /// <summary>Position, rotation and scale of a game object (the stand-in keeps the identity).</summary>
    public class Transform : Component
    {
        /// <summary>The world position.</summary>
        public Vector3 position { get; set; }

        /// <summary>The world rotation (the stand-in keeps it for the scripts to read; its points move by the position only).</summary>
        public Quaternion rotation { get; set; } = Quaternion.identity;

        /// <summary>A direction from world space to local space: unchanged in the stand-in, whose transforms do not rotate.</summary>
        public Vector3 InverseTransformDirection(Vector3 direction) => direction;

        /// <summary>World space to local space: the identity transform of the stand-in only moves by the position.</summary>
        public Vector3 InverseTransformPoint(Vector3 position) =>
            new Vector3(position.x - this.position.x, position.y - this.position.y, position.z - this.position.z);

        /// <summary>Local space to world space.</summary>
        public Vector3 TransformPoint(Vector3 position) =>
            new Vector3(position.x + this.position.x, position.y + this.position.y, position.z + this.position.z);
    }

    /// <summary>Holds the mesh a MeshRenderer draws.</summary>
    public sealed class MeshFilter : Component
    {
        /// <summary>The mesh, shared with other filters.</summary>
        public Mesh sharedMesh { get; set; }
    }

    /// <summary>Draws the mesh of the MeshFilter beside it.</summary>
    public sealed class MeshRenderer : Renderer
    {
    }

    /// <summary>Vertices, normals and triangles. The stand-in keeps copies in buffers it sizes once.</summary>
    public sealed class Mesh : Object
    {
        private Vector3[] _vertices = new Vector3[0];
        private Vector3[] _normals = new Vector3[0];
        private int[] _triangles = new int[0];
        private Color[] _colors = new Color[0];
        private int _vertexCount;

        /// <summary>16-bit indices (at most 65535 vertices) or 32-bit ones.</summary>
        public IndexFormat indexFormat { get; set; }

        /// <summary>The number of vertices last set.</summary>
        public int vertexCount => _vertexCount;

        /// <summary>The box around the vertices, from the last RecalculateBounds.</summary>
        public Bounds bounds { get; set; }

        /// <summary>True after MarkDynamic.</summary>
        public bool IsDynamic { get; private set; }

        /// <summary>A copy of the vertices (in Unity too: this property allocates).</summary>
        public Vector3[] vertices => Copy(_vertices, _vertexCount);

        /// <summary>A copy of the normals.</summary>
        public Vector3[] normals => Copy(_normals, _vertexCount);

        /// <summary>A copy of the triangle indices.</summary>
        public int[] triangles => (int[])_triangles.Clone();

        /// <summary>The vertex colours (a copy, as in Unity; empty when the mesh has none).</summary>
        public Color[] colors
        {
            get { return (Color[])_colors.Clone(); }
            set { _colors = value == null ? new Color[0] : (Color[])value.Clone(); }
        }

        /// <summary>Hints that the vertices change often.</summary>
        public void MarkDynamic() => IsDynamic = true;

        /// <summary>Sets the vertices from an array.</summary>
        public void SetVertices(Vector3[] inVertices) => SetVertices(inVertices, 0, Length(inVertices));

        /// <summary>Sets the vertices from part of an array.</summary>
        public void SetVertices(Vector3[] inVertices, int start, int length)
        {
            CheckRange(inVertices, start, length);
            Store(ref _vertices, inVertices, start, length);
            _vertexCount = length;
        }

        /// <summary>Sets the vertices from a list.</summary>
        public void SetVertices(List<Vector3> inVertices) => SetVertices(inVertices.ToArray());

        /// <summary>Sets the vertices from a native array.</summary>
        public void SetVertices<T>(NativeArray<T> inVertices)
            where T : struct
        {
            throw new NotSupportedException("The stand-in Mesh does not read NativeArray.");
        }

        /// <summary>Sets the normals from an array.</summary>
        public void SetNormals(Vector3[] inNormals) => SetNormals(inNormals, 0, Length(inNormals));

        /// <summary>Sets the normals from part of an array.</summary>
        public void SetNormals(Vector3[] inNormals, int start, int length)
        {
            CheckRange(inNormals, start, length);
            Store(ref _normals, inNormals, start, length);
        }

        /// <summary>Sets the normals from a list.</summary>
        public void SetNormals(List<Vector3> inNormals) => SetNormals(inNormals.ToArray());

        /// <summary>Sets the normals from a native array.</summary>
        public void SetNormals<T>(NativeArray<T> inNormals)
            where T : struct
        {
            throw new NotSupportedException("The stand-in Mesh does not read NativeArray.");
        }

        /// <summary>Sets the triangle indices of a submesh (the stand-in has one).</summary>
        public void SetTriangles(int[] triangles, int submesh)
        {
            if (submesh != 0)
            {
                throw new ArgumentOutOfRangeException(nameof(submesh), submesh, "The stand-in mesh has one submesh.");
            }

            var limit = indexFormat == IndexFormat.UInt16 ? 65535 : int.MaxValue;
            foreach (var index in triangles)
            {
                if (index < 0 || index >= _vertexCount || index > limit)
                {
                    throw new ArgumentException("Triangle index " + index + " does not name one of the " + _vertexCount + " vertices.");
                }
            }

            _triangles = (int[])triangles.Clone();
        }

        /// <summary>Sets the triangle indices from a list.</summary>
        public void SetTriangles(List<int> triangles, int submesh) => SetTriangles(triangles.ToArray(), submesh);

        /// <summary>Recomputes the box around the vertices.</summary>
        public void RecalculateBounds()
        {
            if (_vertexCount == 0)
            {
                bounds = new Bounds(new Vector3(0, 0, 0), new Vector3(0, 0, 0));
                return;
            }

            var min = _vertices[0];
            var max = _vertices[0];
            for (var i = 1; i < _vertexCount; i++)
            {
                var v = _vertices[i];
                min = new Vector3(Math.Min(min.x, v.x), Math.Min(min.y, v.y), Math.Min(min.z, v.z));
                max = new Vector3(Math.Max(max.x, v.x), Math.Max(max.y, v.y), Math.Max(max.z, v.z));
            }

            bounds = new Bounds(
                new Vector3((min.x + max.x) / 2, (min.y + max.y) / 2, (min.z + max.z) / 2),
                new Vector3(max.x - min.x, max.y - min.y, max.z - min.z));
        }

        private static int Length(Vector3[] array) => array == null ? 0 : array.Length;

        private static void CheckRange(Vector3[] array, int start, int length)
        {
            if (array == null)
            {
                throw new ArgumentNullException(nameof(array));
            }

            if (start < 0 || length < 0 || start > array.Length - length)
            {
                throw new ArgumentOutOfRangeException(nameof(length), "start and length must lie within the array.");
            }
        }

        private static void Store(ref Vector3[] buffer, Vector3[] source, int start, int length)
        {
            if (buffer.Length != length)
            {
                buffer = new Vector3[length];
            }

            Array.Copy(source, start, buffer, 0, length);
        }

        private static Vector3[] Copy(Vector3[] source, int length)
        {
            var copy = new Vector3[length];
            Array.Copy(source, copy, length);
            return copy;
        }
    }

    /// <summary>A rotation: Unity's x, y, z, w.</summary>
    public struct Quaternion
    {
        /// <summary>The x component.</summary>
        public float x;

        /// <summary>The y component.</summary>
        public float y;

        /// <summary>The z component.</summary>
        public float z;

        /// <summary>The w component.</summary>
        public float w;

        /// <summary>A rotation.</summary>
        public Quaternion(float x, float y, float z, float w)
        {
            this.x = x;
            this.y = y;
            this.z = z;
            this.w = w;
        }

        /// <summary>No rotation.</summary>
        public static Quaternion identity => new Quaternion(0, 0, 0, 1);
    }

    /// <summary>A colour: Unity's r, g, b, a floats from 0 to 1.</summary>
    public struct Color
    {
        /// <summary>Red.</summary>
        public float r;

        /// <summary>Green.</summary>
        public float g;

        /// <summary>Blue.</summary>
        public float b;

        /// <summary>Alpha.</summary>
        public float a;

        /// <summary>A colour.</summary>
        public Color(float r, float g, float b, float a)
        {
            this.r = r;
            this.g = g;
            this.b = b;
            this.a = a;
        }
    }

    /// <summary>Three floats x, y, z: Unity's layout, the same as System.Numerics.Vector3's.</summary>
    [StructLayout(LayoutKind.Sequential)]
    public struct Vector3
    {
        /// <summary>The x component.</summary>
        public float x;

        /// <summary>The y component.</summary>
        public float y;

        /// <summary>The z component.</summary>
        public float z;

        /// <summary>A vector.</summary>
        public Vector3(float x, float y, float z)
        {
            this.x = x;
            this.y = y;
            this.z = z;
        }

        /// <summary>The length.</summary>
        public float magnitude => (float)Math.Sqrt((x * x) + (y * y) + (z * z));

        /// <summary>(0, 0, 0).</summary>
        public static Vector3 zero => new Vector3(0, 0, 0);

        /// <summary>(0, 1, 0).</summary>
        public static Vector3 up => new Vector3(0, 1, 0);
    }

    /// <summary>An axis-aligned box.</summary>
    public struct Bounds
    {
        /// <summary>A box of a centre and a size.</summary>
        public Bounds(Vector3 center, Vector3 size)
        {
            this.center = center;
            this.size = size;
        }

        /// <summary>The centre.</summary>
        public Vector3 center { get; set; }

        /// <summary>The size along each axis.</summary>
        public Vector3 size { get; set; }
    }

    /// <summary>Frame timing.</summary>
    public static class Time
    {
        /// <summary>The time the last frame took, in seconds.</summary>
        public static float deltaTime { get; internal set; }

        /// <summary>The time since the start, in seconds.</summary>
        public static float time { get; internal set; }

        /// <summary>The number of frames run.</summary>
        public static int frameCount { get; internal set; }

        /// <summary>The interval of FixedUpdate, in seconds (Unity's default: 0.02).</summary>
        public static float fixedDeltaTime { get; set; } = 0.02f;
    }

    /// <summary>The console. The stand-in keeps what is logged, so that tests can check that nothing went wrong.</summary>
    public static class Debug
    {
        private static readonly List<string> _errors = new List<string>();

        /// <summary>The errors and exceptions logged so far.</summary>
        public static IReadOnlyList<string> Errors => _errors;

        /// <summary>Logs a message.</summary>
        public static void Log(object message)
        {
        }

        /// <summary>Logs a warning.</summary>
        public static void LogWarning(object message)
        {
        }

        /// <summary>Logs an error.</summary>
        public static void LogError(object message) => _errors.Add(Convert.ToString(message));

        /// <summary>Logs an exception.</summary>
        public static void LogException(Exception exception) => _errors.Add(exception.ToString());

        internal static void ClearErrors() => _errors.Clear();
    }

    /// <summary>The base of attributes that change how the Inspector draws a field.</summary>
    [AttributeUsage(AttributeTargets.Field, Inherited = true, AllowMultiple = false)]
    public abstract class PropertyAttribute : Attribute
    {
    }

    /// <summary>Shows an int or float field as a slider limited to [min, max].</summary>
    [AttributeUsage(AttributeTargets.Field, Inherited = true, AllowMultiple = false)]
    public sealed class RangeAttribute : PropertyAttribute
    {
        /// <summary>The smallest value.</summary>
        public readonly float min;

        /// <summary>The largest value.</summary>
        public readonly float max;

        /// <summary>A range.</summary>
        public RangeAttribute(float min, float max)
        {
            this.min = min;
            this.max = max;
        }
    }

    /// <summary>Keeps a float or int field at or above min in the Inspector.</summary>
    [AttributeUsage(AttributeTargets.Field, Inherited = true, AllowMultiple = false)]
    public sealed class MinAttribute : PropertyAttribute
    {
        /// <summary>The smallest value.</summary>
        public readonly float min;

        /// <summary>A lower bound.</summary>
        public MinAttribute(float min)
        {
            this.min = min;
        }
    }

    /// <summary>A tooltip for a field in the Inspector.</summary>
    [AttributeUsage(AttributeTargets.Field, Inherited = true, AllowMultiple = false)]
    public sealed class TooltipAttribute : PropertyAttribute
    {
        /// <summary>The tooltip.</summary>
        public readonly string tooltip;

        /// <summary>A tooltip.</summary>
        public TooltipAttribute(string tooltip)
        {
            this.tooltip = tooltip;
        }
    }

    /// <summary>A header above a field in the Inspector.</summary>
    [AttributeUsage(AttributeTargets.Field, Inherited = true, AllowMultiple = true)]
    public sealed class HeaderAttribute : PropertyAttribute
    {
        /// <summary>The header.</summary>
        public readonly string header;

        /// <summary>A header.</summary>
        public HeaderAttribute(string header)
        {
            this.header = header;
        }
    }

    /// <summary>Serializes a private field, which the Inspector then shows.</summary>
    [AttributeUsage(AttributeTargets.Field)]
    public sealed class SerializeField : Attribute
    {
    }

    /// <summary>Places a script in the Add Component menu.</summary>
    [AttributeUsage(AttributeTargets.Class, AllowMultiple = false)]
    public sealed class AddComponentMenu : Attribute
    {
        /// <summary>A menu path.</summary>
        public AddComponentMenu(string menuName)
        {
            componentMenu = menuName;
        }

        /// <summary>The menu path.</summary>
        public string componentMenu { get; }
    }

    /// <summary>At most one such component per game object.</summary>
    [AttributeUsage(AttributeTargets.Class, Inherited = false)]
    public sealed class DisallowMultipleComponent : Attribute
    {
    }

    /// <summary>Components that AddComponent adds first when they are missing.</summary>
    [AttributeUsage(AttributeTargets.Class, AllowMultiple = true)]
    public sealed class RequireComponent : Attribute
    {
        /// <summary>The required type (Unity's field name).</summary>
        public Type m_Type0;

        /// <summary>Requires a component.</summary>
        public RequireComponent(Type requiredComponent)
        {
            m_Type0 = requiredComponent;
        }
    }

    // Names only: real UnityEngine types that a library type could be named like. A type of ours with one of these
    // names makes every script with `using UnityEngine;` and our namespace fail with CS0104 where it names it.
    public class ParticleSystem : Component { }
    public class ParticleSystemRenderer : Renderer { }
    public struct ParticleCollisionEvent { }
    public static class ParticlePhysicsExtensions { }
    public class ParticleSystemForceField : Behaviour { }
    public class Cloth : Component { }
    public struct ClothSphereColliderPair { }
    public struct ClothSkinningCoefficient { }
    public class Collider : Component { }
    public class SphereCollider : Collider { }
    public class BoxCollider : Collider { }
    public class CapsuleCollider : Collider { }
    public class MeshCollider : Collider { }
    public class WheelCollider : Collider { }
    public class TerrainCollider : Collider { }
    public class CharacterController : Collider { }
    public class PhysicMaterial : Object { }
    public class PhysicsMaterial : Object { }
    public enum PhysicMaterialCombine { Average }
    public class Collider2D : Behaviour { }
    public class CircleCollider2D : Collider2D { }
    public class BoxCollider2D : Collider2D { }
    public class Rigidbody : Component { }
    public class Rigidbody2D : Component { }
    public class ArticulationBody : Behaviour { }
    public class ConstantForce : Behaviour { }
    public class Joint : Component { }
    public class HingeJoint : Joint { }
    public class FixedJoint : Joint { }
    public class SpringJoint : Joint { }
    public class CharacterJoint : Joint { }
    public class ConfigurableJoint : Joint { }
    public class Joint2D : Behaviour { }
    public class SpringJoint2D : Joint2D { }
    public class DistanceJoint2D : Joint2D { }
    public struct JointSpring { }
    public struct JointLimits { }
    public struct JointMotor { }
    public struct SoftJointLimit { }
    public struct SoftJointLimitSpring { }
    public enum RigidbodyConstraints { None }
    public enum RigidbodyInterpolation { None }
    public enum CollisionDetectionMode { Discrete }
    public enum ForceMode { Force }
    public enum QueryTriggerInteraction { UseGlobal }
    public static class Physics { }
    public static class Physics2D { }
    public struct PhysicsScene { }
    public class Collision { }
    public class Collision2D { }
    public struct ContactPoint { }
    public struct ContactPoint2D { }
    public struct ContactPairHeader { }
    public struct ContactPair { }
    public struct ContactPairPoint { }
    public struct RaycastHit { }
    public struct RaycastHit2D { }
    public struct WheelHit { }
    public enum CollisionFlags { None }
    public struct Plane { }
    public struct Ray { }
    public struct Ray2D { }
    public struct BoundsInt { }
    public struct BoundingSphere { }
    public class CullingGroup { }
    public struct Rect { }
    public struct RectInt { }
    public struct Vector2 { }
    public struct Vector4 { }
    public struct Vector2Int { }
    public struct Vector3Int { }
    public struct Matrix4x4 { }
    public struct Pose { }
    public struct Color32 { }
    public class Gradient { }
    public class AnimationCurve { }
    public struct Keyframe { }
    public struct LayerMask { }
    public struct Hash128 { }
    public struct Mathf { }
    public static class Random { }
    public enum Space { World }
    public class Renderer : Component { }
    public class SkinnedMeshRenderer : Renderer { }
    public class LineRenderer : Renderer { }
    public class TrailRenderer : Renderer { }
    public class SpriteRenderer : Renderer { }
    public class Material : Object { }
    public class Shader : Object { }
    public class Texture : Object { }
    public class Texture2D : Texture { }
    public class Sprite : Object { }
    public class Camera : Behaviour { }
    public class Light : Behaviour { }
    public class ReflectionProbe : Behaviour { }
    public class LightProbes : Object { }
    public class Skybox : Behaviour { }
    public class Projector : Behaviour { }
    public class LODGroup : Component { }
    public class Terrain : Behaviour { }
    public class TerrainData : Object { }
    public class Tree : Component { }
    public class WindZone : Component { }
    public class Grid : Behaviour { }
    public class Canvas : Behaviour { }
    public class RectTransform : Transform { }
    public class Animator : Behaviour { }
    public class Animation : Behaviour { }
    public class AudioSource : Behaviour { }
    public class AudioClip : Object { }
    public class Avatar : Object { }
    public class Motion : Object { }
    public class ScriptableObject : Object { }
    public class TextAsset : Object { }
    public class Font : Object { }
    public class Coroutine { }
    public class YieldInstruction { }
    public sealed class WaitForSeconds : YieldInstruction { }
    public sealed class WaitForFixedUpdate : YieldInstruction { }
    public class Event { }
    public class GUI { }
    public class GUILayout { }
    public sealed class Gizmos { }
    public sealed class Application { }
    public class Input { }
    public sealed class Screen { }
    public sealed class Display { }
    public sealed class Resources { }
    public sealed class QualitySettings : Object { }
    public sealed class SystemInfo { }
    public class PlayerPrefs { }
}

namespace UnityEngine.Rendering
{
    /// <summary>The width of a mesh's indices.</summary>
    public enum IndexFormat
    {
        /// <summary>16-bit indices: at most 65535 vertices.</summary>
        UInt16 = 0,

        /// <summary>32-bit indices.</summary>
        UInt32 = 1,
    }
}

namespace Unity.Collections
{
    /// <summary>A buffer in native memory (only its name and type here: the stand-in Mesh does not read it).</summary>
    public struct NativeArray<T>
        where T : struct
    {
        /// <summary>The number of elements.</summary>
        public int Length { get; }
    }
}

namespace UnityEngine.StandIn
{
    /// <summary>
    /// Unity's frame loop, for the stand-in: each frame sets Time, then calls Start once on every enabled
    /// MonoBehaviour that has not started yet, then Update on every enabled one, in the order they were added.
    /// </summary>
    public static class PlayerLoop
    {
        private static readonly List<Entry> _entries = new List<Entry>();

        /// <summary>Runs one frame of <paramref name="deltaTime"/> seconds.</summary>
        public static void RunFrame(float deltaTime)
        {
            Time.deltaTime = deltaTime;
            Time.time += deltaTime;
            Time.frameCount++;
            for (var i = 0; i < _entries.Count; i++)
            {
                var entry = _entries[i];
                if (!entry.Behaviour.enabled || entry.Behaviour.IsDestroyed || entry.Started)
                {
                    continue;
                }

                entry.Started = true;
                if (entry.Start != null)
                {
                    entry.Start();
                }
            }

            for (var i = 0; i < _entries.Count; i++)
            {
                var entry = _entries[i];
                if (entry.Behaviour.enabled && !entry.Behaviour.IsDestroyed && entry.Started && entry.Update != null)
                {
                    entry.Update();
                }
            }
        }

        /// <summary>Destroys every game object (OnDestroy runs) and starts a new scene; clears the logged errors.</summary>
        public static void Reset()
        {
            foreach (var entry in _entries)
            {
                if (entry.OnDestroy != null)
                {
                    entry.OnDestroy();
                }
            }

            _entries.Clear();
            Debug.ClearErrors();
            Time.deltaTime = 0;
            Time.time = 0;
            Time.frameCount = 0;
        }

        internal static void Register(Component component)
        {
            var behaviour = component as MonoBehaviour;
            if (behaviour != null)
            {
                _entries.Add(new Entry(behaviour));
            }
        }

        private sealed class Entry
        {
            public Entry(MonoBehaviour behaviour)
            {
                Behaviour = behaviour;
                Start = Message(behaviour, "Start");
                Update = Message(behaviour, "Update");
                OnDestroy = Message(behaviour, "OnDestroy");
            }

            public MonoBehaviour Behaviour { get; }

            public Action Start { get; }

            public Action Update { get; }

            public Action OnDestroy { get; }

            public bool Started { get; set; }

            // Unity finds its messages by name, public or not, without arguments.
            private static Action Message(MonoBehaviour behaviour, string name)
            {
                var method = behaviour.GetType().GetMethod(
                    name, BindingFlags.Instance | BindingFlags.Public | BindingFlags.NonPublic, null, Type.EmptyTypes, null);
                return method == null ? null : (Action)Delegate.CreateDelegate(typeof(Action), behaviour, method);
            }
        }
    }
}
