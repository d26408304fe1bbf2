using ParticlePhysics.Constraints;
using ParticlePhysics.Contacts;
using ParticlePhysics.Forces;
using ParticlePhysics.Scenes;

namespace ParticlePhysics.Demo.Animation;

/// <summary>
/// Reads what a replay draws, besides the moving positions, from a freshly built world: the radii and pins, the
/// springs of its force generators, the rods and cables of its constraint sets (as links by their particles or
/// anchors), the constant loads of a scene (as arrows), the obstacles of its contact sets (as the core describes them
/// for renderers, with their velocity), and, for a cloth, its grid or its membrane's triangles as a surface.
/// This is the one place that knows which core types carry something drawable: a new kind of link or collider joins
/// the replay by a case here.
/// </summary>
internal static class SceneReader
{
    /// <summary>The scene of <paramref name="world"/>; <paramref name="clothSide"/> n &gt; 0 adds the n x n grid's triangles.</summary>
    public static ReplayScene Read(ParticleWorld world, int clothSide = 0)
    {
        var scene = new ReplayScene(world.Count);
        for (var i = 0; i < world.Count; i++)
        {
            if (world.IsPinned(i))
            {
                scene.Pin(i);
            }

            scene.SetRadius(i, world.GetRadius(i));
        }

        foreach (var force in world.Forces)
        {
            switch (force)
            {
                case SpringNetwork springs:
                    for (var s = 0; s < springs.Count; s++)
                    {
                        var (first, second) = springs.GetEnds(s);
                        scene.AddLink(first, second, LinkKind.Spring);
                    }

                    for (var s = 0; s < springs.AnchoredCount; s++)
                    {
                        var (particle, anchor) = springs.GetAnchoredSpring(s);
                        scene.AddAnchoredLink(particle, anchor, LinkKind.Spring);
                    }

                    break;
                case TriangleMembrane membrane:
                    // A cloth from a mesh: its triangles are its surface.
                    for (var t = 0; t < membrane.Count; t++)
                    {
                        var (first, second, third) = membrane.GetCorners(t);
                        scene.AddTriangle(first, second, third);
                    }

                    break;
                case ConstantLoads loads:
                    for (var k = 0; k < loads.Count; k++)
                    {
                        var (particle, load) = loads.Get(k);
                        scene.AddLoad(particle, load);
                    }

                    break;
                case ZeroLengthSprings springs:
                    for (var s = 0; s < springs.Count; s++)
                    {
                        var (first, second) = springs.GetEnds(s);
                        scene.AddLink(first, second, LinkKind.Spring);
                    }

                    for (var s = 0; s < springs.AnchoredCount; s++)
                    {
                        var (particle, anchor) = springs.GetAnchoredSpring(s);
                        scene.AddAnchoredLink(particle, anchor, LinkKind.Spring);
                    }

                    break;
            }
        }

        foreach (var set in world.Constraints)
        {
            switch (set)
            {
                case RodNetwork rods:
                    for (var r = 0; r < rods.Count; r++)
                    {
                        var (first, second) = rods.GetEnds(r);
                        var kind = rods.IsCable(r) ? LinkKind.Cable : LinkKind.Rod;
                        if (second < 0)
                        {
                            scene.AddAnchoredLink(first, rods.GetAnchor(r), kind, rods.GetLength(r));
                        }
                        else
                        {
                            scene.AddLink(first, second, kind, rods.GetLength(r));
                        }
                    }

                    break;
                case ContactSet contacts:
                    foreach (var obstacle in contacts.Obstacles)
                    {
                        scene.AddCollider(obstacle.ShapeAt(0), obstacle.Velocity);
                    }

                    break;
            }
        }

        if (clothSide > 1)
        {
            AddGrid(scene, clothSide);
        }

        return scene;
    }

    /// <summary>
    /// Two triangles per cell of the n x n grid whose particle (row, col) has index row * n + col, wound so that the
    /// side facing +y at the start (the cloth lies in y = 0, rows along +z) is the front.
    /// </summary>
    private static void AddGrid(ReplayScene scene, int n)
    {
        for (var row = 0; row + 1 < n; row++)
        {
            for (var col = 0; col + 1 < n; col++)
            {
                var a = (row * n) + col;
                scene.AddTriangle(a, a + n + 1, a + 1);
                scene.AddTriangle(a, a + n, a + n + 1);
            }
        }
    }
}
