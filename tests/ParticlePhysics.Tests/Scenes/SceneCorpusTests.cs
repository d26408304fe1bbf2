using System;
using System.Collections.Generic;
using System.IO;
using System.Linq;
using ParticlePhysics.Integrators;
using ParticlePhysics.Scenes;
using ParticlePhysics.Tests.Demo;
using ParticlePhysics.Tests.Engine;

namespace ParticlePhysics.Tests.Scenes;

/// <summary>
/// Bad scene files: a corpus of malformed ones, every error path of the loader, and thousands of deterministic mutations
/// of the sample scenes. Each is refused with exactly one line (exit code 2, nothing on stdout) that names the file
/// and, where the error has one, the line, the column and the JSON path, or it loads and runs.
/// </summary>
public class SceneCorpusTests
{
    private readonly Xunit.Abstractions.ITestOutputHelper _output;

    public SceneCorpusTests(Xunit.Abstractions.ITestOutputHelper output)
    {
        _output = output;
    }

    private static readonly string _folder = Path.Combine(ReadmeExamplesTests.RepositoryRoot(), "samples", "scenes");

    private const string Ok = "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0], [1, 1, 0]] }] }";

    /// <summary>Malformed JSON and wrong scenes, each with a piece of the message it must give (file:line:column: path ...).</summary>
    public static TheoryData<string, string, string> Corpus() => new()
    {
        { "empty file", string.Empty, "the file is empty" },
        { "no particles", "{}", "scene.json: the scene has no particles to run" },
        { "only a comment", "// nothing\n", "the file is empty" },
        { "only spaces", "  \n\t \n", "the file is empty" },
        { "not an object", "[1, 2, 3]", "scene.json:1:1: [1, 2, 3]: a scene is a JSON object" },
        { "a number", "42", "a scene is a JSON object" },
        { "unterminated object", "{ \"objects\": [", "scene.json:1:15: objects[0]: malformed JSON: the file ends where a value should be" },
        { "unterminated string", "{ \"drag", "scene.json:1:3: malformed JSON: a string that never ends" },
        { "missing colon", "{ \"drag\" 1 }", "scene.json:1:10: malformed JSON: expected ':' after the key \"drag\", found '1'" },
        { "missing comma", "{ \"drag\": 1 \"dt\": 2 }", "scene.json:1:13: malformed JSON: expected ',' or '}' after a member of an object, found '\"'" },
        { "single quotes", "{ 'drag': 1 }", "scene.json:1:3: malformed JSON: expected a key in double quotes or '}', found ' (strings and keys take double quotes)" },
        { "bare key", "{ drag: 1 }", "expected a key in double quotes" },
        { "NaN", "{ \"drag\": NaN }", "scene.json:1:11: drag: malformed JSON: expected a value" },
        { "Infinity", "{ \"drag\": Infinity }", "expected a value" },
        { "leading zero", "{ \"drag\": 01 }", "a number may not start with 0" },
        { "plus sign", "{ \"drag\": +1 }", "expected a value" },
        { "bare dot", "{ \"drag\": .5 }", "expected a value" },
        { "trailing dot", "{ \"drag\": 1. }", "expected a digit after the decimal point" },
        { "hexadecimal", "{ \"drag\": 0x10 }", "not a number" },
        { "overflow", "{ \"drag\": 1e999 }", "scene.json:1:11: drag: malformed JSON: a number beyond the range of a double (about 1.8e308), found 1e999" },
        { "block comment", "{ /* no */ }", "scene.json:1:3: malformed JSON: only // comments are allowed" },
        { "text after", Ok + " x", "text after the end" },
        { "two objects", Ok + Ok, "text after the end" },
        { "duplicate key", "{ \"drag\": 1, \"drag\": 2 }", "scene.json:1:14: drag: malformed JSON: this key appears twice" },
        { "bad escape", "{ \"objects\": [{ \"type\": \"par\\qticles\" }] }", "an unknown escape" },
        { "short unicode escape", "{ \"a\\u12\": 1 }", "\\u must be followed by four hexadecimal digits" },
        { "raw line break in a string", "{ \"a\nb\": 1 }", "a control character" },
        { "truthy", "{ \"particleCollisions\": tru }", "not a JSON value" },
        { "deep nesting", "{ \"objects\": " + new string('[', 100_000) + " }", "nested more than 64 deep" },
        { "deep objects", string.Concat(Enumerable.Repeat("{ \"a\": ", 70)) + "1" + new string('}', 70), "nested more than 64 deep" },
        { "unknown top-level key", "{ \"gravitty\": [0, -9.81, 0] }", "scene.json:1:3: gravitty: unknown key for a scene (did you mean 'gravity'?)" },
        { "air density", "{ \"air\": { \"density\": -1.2 } }", "air.density = -1.2: must be a number >= 0 (kg/m^3)" },
        { "air typo", "{ \"air\": { \"velocty\": [5, 0, 0] } }", "air.velocty: unknown key for the air (did you mean 'velocity'?)" },
        { "air lift", "{ \"air\": { \"lift\": -1 } }", "air.lift = -1: must be a number >= 0" },
        { "air gust empty", "{ \"air\": { \"gust\": [] } }", "air.gust = []: must be a list of one or more waves" },
        { "air gust wave", "{ \"air\": { \"gust\": [{ \"frequency\": 1 }] } }", "air.gust[0]: a gust's wave needs \"amplitude\"" },
        { "air gust frequency", "{ \"air\": { \"gust\": [{ \"amplitude\": [1, 0, 0], \"frequency\": -2 }] } }", "air.gust[0].frequency = -2: must be a number >= 0 (Hz)" },
        { "sleep without speed", "{ \"sleep\": { \"time\": 1 } }", "sleep: sleeping needs \"speed\"" },
        { "sleep speed", "{ \"sleep\": { \"speed\": 0 } }", "sleep.speed = 0: must be a positive number (m/s)" },
        { "sleep typo", "{ \"sleep\": { \"speed\": 0.05, \"tme\": 1 } }", "sleep.tme: unknown key for sleeping (did you mean 'time'?)" },
        { "sleep under rk4", "{ \"integrator\": \"rk4\", \"sleep\": { \"speed\": 0.05 } }", "sleep = {...}: needs xpbd: the integrator is rk4, under which nothing sleeps" },
        { "objects not a list", "{ \"objects\": {} }", "objects = {}: must be a list [...] of objects" },
        { "object not an object", "{ \"objects\": [3] }", "scene.json:1:15: objects[0] = 3: each object is an object" },
        { "no type", "{ \"objects\": [{ \"positions\": [] }] }", "objects[0]: each object needs a \"type\"" },
        { "type not a string", "{ \"objects\": [{ \"type\": 3 }] }", "objects[0].type = 3: must be a string" },
        { "unknown type", "{ \"objects\": [{ \"type\": \"partciles\" }] }", "objects[0].type = \"partciles\": is not a kind of object (did you mean 'particles'?)" },
        { "cloth without mesh", "{ \"objects\": [{ \"type\": \"cloth\" }] }", "objects[0]: a cloth object needs \"mesh\"" },
        { "cloth triangle naming a missing vertex", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1]], \"triangles\": [[0, 1, 3]] } }] }", "objects[0].mesh.triangles[0] = [0, 1, 3]: triangle 0 names vertex 3, but the mesh has 3 vertices" },
        { "cloth degenerate triangle", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [2, 0, 0]], \"triangles\": [[0, 1, 2]] } }] }", "objects[0].mesh.triangles[0] = [0, 1, 2]: triangle 0 (0, 1, 2) has no area" },
        { "cloth unused vertex", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [5, 5, 5]], \"triangles\": [[0, 1, 2]] } }] }", "objects[0].mesh.vertices[3] = [5, 5, 5]: vertex 3 is used by no triangle" },
        { "cloth duplicate vertices", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 0]], \"triangles\": [[0, 1, 2], [3, 2, 1]] } }] }", "objects[0].mesh.vertices[3] = [0, 0, 0]: vertices 0 and 3 are both at" },
        { "cloth missing obj", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"obj\": \"missing.obj\" } }] }", "missing.obj: cannot read this OBJ file" },
        { "cloth poisson", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]], \"triangles\": [[0, 1, 2], [0, 2, 3]] }, \"stretch\": { \"modulus\": 100, \"poisson\": 0.5 } }] }", "objects[0].stretch.poisson = 0.5: must be from 0 to less than 0.5" },
        { "cloth modulus", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]], \"triangles\": [[0, 1, 2], [0, 2, 3]] }, \"stretch\": { \"modulus\": -1 } }] }", "objects[0].stretch.modulus = -1: must be a positive number (N/m)" },
        { "cloth springs and membrane", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]], \"triangles\": [[0, 1, 2], [0, 2, 3]] }, \"stretch\": { \"modulus\": 1, \"stiffness\": 1 } }] }", "(springs on the edges) or {\"modulus\": Y, \"poisson\": nu} (a membrane), not both" },
        { "cloth pin outside", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]], \"triangles\": [[0, 1, 2], [0, 2, 3]] }, \"pinned\": [4] }] }", "objects[0].pinned[0] = 4: names no vertex of this cloth" },
        { "cloth self collision without a thickness", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]], \"triangles\": [[0, 1, 2], [0, 2, 3]] }, \"selfCollision\": true }] }", "objects[0].selfCollision: needs the cloth's \"thickness\" (m, above 0)" },
        { "cloth aerodynamics not a boolean", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]], \"triangles\": [[0, 1, 2], [0, 2, 3]] }, \"aerodynamics\": 1 }] }", "objects[0].aerodynamics = 1: must be true or false" },
        { "cloth tear", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]], \"triangles\": [[0, 1, 2], [0, 2, 3]] }, \"tear\": { \"strain\": 0.5 } }] }", "not built yet: the cloth's tear arrives with the issue \"cloth in the world\"" },
        { "cloth typo", "{ \"objects\": [{ \"type\": \"cloth\", \"mesh\": { \"vertices\": [[0, 0, 0], [1, 0, 0], [1, 0, 1], [0, 0, 1]], \"triangles\": [[0, 1, 2], [0, 2, 3]] }, \"pined\": [0] }] }", "objects[0].pined: unknown key for a cloth object (did you mean 'pinned'?)" },
        { "rope without points", "{ \"objects\": [{ \"type\": \"rope\" }] }", "objects[0]: a rope object needs \"points\"" },
        { "rope of one point", "{ \"objects\": [{ \"type\": \"rope\", \"points\": [[0, 0, 0]] }] }", "objects[0].points = [... 1 elements]: lists fewer than two points" },
        { "rope of a repeated point", "{ \"objects\": [{ \"type\": \"rope\", \"points\": [[0, 0, 0], [0, 0, 0]] }] }", "objects[0].points[1] = [0, 0, 0]: is where point 0 is" },
        { "rope negative rigidity", "{ \"objects\": [{ \"type\": \"rope\", \"points\": [[0, 0, 0], [1, 0, 0]], \"bending\": { \"rigidity\": -1 } }] }", "objects[0].bending.rigidity = -1: must be a number >= 0 (N m^2)" },
        { "rigid without a shape", "{ \"objects\": [{ \"type\": \"rigid\", \"spacing\": 0.1 }] }", "objects[0]: a rigid object needs \"box\"" },
        { "rigid without a spacing", "{ \"objects\": [{ \"type\": \"rigid\", \"box\": { \"center\": [0, 0, 0], \"size\": [1, 1, 1] } }] }", "objects[0]: a rigid object needs \"spacing\"" },
        { "rigid box and mesh", "{ \"objects\": [{ \"type\": \"rigid\", \"spacing\": 0.1, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 1, 1] }, \"mesh\": { \"obj\": \"a.obj\" } }] }", "needs \"box\"" },
        { "rigid flat box", "{ \"objects\": [{ \"type\": \"rigid\", \"spacing\": 0.1, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 0, 1] } }] }", "objects[0].box.size = [1, 0, 1]: must be three positive numbers" },
        { "rigid on a line", "{ \"objects\": [{ \"type\": \"rigid\", \"spacing\": 0.1, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 0.1, 0.1] } }] }", "fills with 10 particles on one line" },
        { "rigid mass and density", "{ \"objects\": [{ \"type\": \"rigid\", \"spacing\": 0.5, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 1, 1] }, \"mass\": 1, \"density\": 2 }] }", "objects[0].density: give \"mass\"" },
        { "rigid restitution", "{ \"objects\": [{ \"type\": \"rigid\", \"spacing\": 0.5, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 1, 1] }, \"restitution\": 2 }] }", "objects[0].restitution = 2: must be" },
        { "rigid open mesh", "{ \"objects\": [{ \"type\": \"rigid\", \"spacing\": 0.1, \"mesh\": { \"vertices\": [[0,0,0],[1,0,0],[0,1,0],[0,0,1]], \"triangles\": [[0,2,1],[0,1,3],[0,3,2]] } }] }", "objects[0].mesh: cannot be filled: The mesh is not closed" },
        { "rigid typo", "{ \"objects\": [{ \"type\": \"rigid\", \"spacing\": 0.5, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 1, 1] }, \"angularVelocty\": [0, 1, 0] }] }", "did you mean 'angularVelocity'?" },
        { "soft stiffness", "{ \"objects\": [{ \"type\": \"soft\", \"spacing\": 0.5, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 1, 1] }, \"stiffness\": 1.5 }] }", "objects[0].stiffness = 1.5: must be in (0, 1]" },
        { "soft plasticity without yield", "{ \"objects\": [{ \"type\": \"soft\", \"spacing\": 0.5, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 1, 1] }, \"plasticity\": {} }] }", "objects[0].plasticity: a soft body's plasticity needs \"yield\"" },
        { "soft plasticity creep", "{ \"objects\": [{ \"type\": \"soft\", \"spacing\": 0.5, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 1, 1] }, \"plasticity\": { \"yield\": 0.01, \"creep\": 1.5 } }] }", "objects[0].plasticity.creep = 1.5: must be in (0, 1]" },
        { "rigid plasticity", "{ \"objects\": [{ \"type\": \"rigid\", \"spacing\": 0.5, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 1, 1] }, \"plasticity\": { \"yield\": 0.01 } }] }", "objects[0].plasticity: unknown key for a rigid object" },
        { "rigid stiffness", "{ \"objects\": [{ \"type\": \"rigid\", \"spacing\": 0.5, \"box\": { \"center\": [0, 0, 0], \"size\": [1, 1, 1] }, \"stiffness\": 0.5 }] }", "objects[0].stiffness: unknown key for a rigid object" },
        { "granular without a box", "{ \"objects\": [{ \"type\": \"granular\", \"spacing\": 0.1 }] }", "objects[0]: a granular object needs \"box\"" },
        { "granular max below min", "{ \"objects\": [{ \"type\": \"granular\", \"spacing\": 0.1, \"box\": { \"min\": [0, 0, 0], \"max\": [1, 0, 1] } }] }", "objects[0].box.max = [1, 0, 1]: must be above \"min\" [0, 0, 0]" },
        { "granular radius", "{ \"objects\": [{ \"type\": \"granular\", \"spacing\": 0.1, \"radius\": 0.06, \"box\": { \"min\": [0, 0, 0], \"max\": [1, 1, 1] } }] }", "objects[0].radius = 0.06: must be at most half the spacing (0.05 m)" },
        { "granular too many", "{ \"objects\": [{ \"type\": \"granular\", \"spacing\": 0.001, \"box\": { \"min\": [0, 0, 0], \"max\": [1, 1, 1] } }] }", "objects[0]: fills with 1,000,000,000 grains" },
        { "granular typo", "{ \"objects\": [{ \"type\": \"granular\", \"spacing\": 0.1, \"box\": { \"min\": [0, 0, 0], \"max\": [1, 1, 1] }, \"rollingfriction\": 0.1 }] }", "did you mean 'rollingFriction'?" },
        { "fluid without a box", "{ \"objects\": [{ \"type\": \"fluid\", \"spacing\": 0.1 }] }", "objects[0]: a fluid object needs \"box\"" },
        { "fluid viscosity", "{ \"objects\": [{ \"type\": \"fluid\", \"spacing\": 0.1, \"box\": { \"min\": [0, 0, 0], \"max\": [1, 1, 1] }, \"viscosity\": 2 }] }", "objects[0].viscosity = 2: must be in [0, 1]" },
        { "fluid cohesion", "{ \"objects\": [{ \"type\": \"fluid\", \"spacing\": 0.1, \"box\": { \"min\": [0, 0, 0], \"max\": [1, 1, 1] }, \"cohesion\": 0.5 }] }", "objects[0].cohesion = 0.5: must be 0: cohesion and surface tension are not built yet" },
        { "fluid too many", "{ \"objects\": [{ \"type\": \"fluid\", \"spacing\": 0.001, \"box\": { \"min\": [0, 0, 0], \"max\": [1, 1, 1] } }] }", "objects[0]: fills with 1,000,000,000 particles" },
        { "mesh collider without a mesh", "{ \"colliders\": [{ \"type\": \"mesh\" }] }", "colliders[0]: mesh needs \"mesh\"" },
        { "mesh collider with a vertex out of range", "{ \"colliders\": [{ \"type\": \"mesh\", \"mesh\": { \"vertices\": [[0,0,0],[1,0,0],[0,0,1]], \"triangles\": [[0,1,3]] } }] }", "colliders[0].mesh.triangles[0]" },
        { "mesh collider of a triangle without area", "{ \"colliders\": [{ \"type\": \"mesh\", \"mesh\": { \"vertices\": [[0,0,0],[1,0,0],[2,0,0]], \"triangles\": [[0,1,2]] } }] }", "has no area" },
        { "heightfield without heights", "{ \"colliders\": [{ \"type\": \"heightfield\", \"cellSize\": [1, 1] }] }", "heightfield needs \"heights\"" },
        { "heightfield with a short row", "{ \"colliders\": [{ \"type\": \"heightfield\", \"cellSize\": [1, 1], \"heights\": [[0, 1], [0]] }] }", "colliders[0].heights[1]" },
        { "unknown collider", "{ \"colliders\": [{ \"type\": \"cube\" }] }", "is not a kind of collider" },
        { "no positions", "{ \"objects\": [{ \"type\": \"particles\" }] }", "objects[0]: a particles object needs \"positions\"" },
        { "no particle", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [] }] }", "objects[0].positions = []: lists no particle" },
        { "short vector", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1]] }] }", "objects[0].positions[0] = [0, 1]: must be [x, y, z]" },
        { "string coordinate", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, \"1\", 0]] }] }", "objects[0].positions[0][1] = \"1\": must be a number" },
        { "negative mass", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"mass\": -1 }] }", "scene.json:1:72: objects[0].mass = -1: must be a positive number (kg) whose inverse is finite (at least 5.6e-309)" },
        { "zero mass", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"mass\": 0 }] }", "mass = 0: must be a positive number" },
        { "tiny mass", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"mass\": 1e-320 }] }", "whose inverse is finite" },
        { "mass and masses", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"mass\": 1, \"masses\": [1] }] }", "give \"mass\" (the same for every particle) or \"masses\" (one per particle), not both" },
        { "masses count", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"masses\": [1, 2] }] }", "lists 2 values for 1 particles" },
        { "negative radius", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"radius\": -0.1 }] }", "radius = -0.1: must be a number >= 0 (m)" },
        { "velocities count", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"velocities\": [] }] }", "lists 0 velocities for 1 positions" },
        { "pin outside", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"pinned\": [1] }] }", "objects[0].pinned[0] = 1: names no particle of this object" },
        { "fractional index", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"pinned\": [0.5] }] }", "must be a particle index: a whole number >= 0" },
        { "negative index", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"pinned\": [-1] }] }", "must be a particle index" },
        { "typo in particles", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0]], \"pined\": [0] }] }", "objects[0].pined: unknown key for a particles object (did you mean 'pinned'?)" },
        { "spring without stiffness", "{ \"objects\": [{ \"type\": \"springs\", \"pairs\": [[0, 1]] }] }", "objects[0]: a springs object needs \"stiffness\"" },
        { "spring without pairs", "{ \"objects\": [{ \"type\": \"springs\", \"stiffness\": 1 }] }", "needs \"pairs\"" },
        { "negative stiffness", "{ \"objects\": [{ \"type\": \"springs\", \"pairs\": [[0, 1]], \"stiffness\": -5 }] }", "objects[0].stiffness = -5: must be a number >= 0 (N/m)" },
        { "negative damping", "{ \"objects\": [{ \"type\": \"springs\", \"pairs\": [[0, 1]], \"stiffness\": 5, \"damping\": -1 }] }", "damping = -1: must be a number >= 0 (N s/m)" },
        { "negative rest length", "{ \"objects\": [{ \"type\": \"springs\", \"pairs\": [[0, 1]], \"stiffness\": 5, \"restLength\": -1 }] }", "restLength = -1" },
        { "rest lengths count", "{ \"objects\": [{ \"type\": \"springs\", \"pairs\": [[0, 1]], \"stiffness\": 5, \"restLengths\": [1, 2] }] }", "lists 2 lengths for 1 pairs" },
        { "pair to itself", "{ \"objects\": [{ \"type\": \"springs\", \"pairs\": [[1, 1]], \"stiffness\": 5 }] }", "objects[0].pairs[0] = [1, 1]: joins a particle to itself" },
        { "pair of three", "{ \"objects\": [{ \"type\": \"springs\", \"pairs\": [[0, 1, 2]], \"stiffness\": 5 }] }", "must be a pair [i, j]" },
        { "pair beyond the particles", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0], [1, 1, 0]] }, { \"type\": \"springs\", \"pairs\": [[0, 2]], \"stiffness\": 5 }] }", "scene.json:1:112: objects[1].pairs[0][1] = 2: names no particle: the scene's particles are numbered 0 to 1" },
        { "rod of zero length", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0], [1, 1, 0]] }, { \"type\": \"rods\", \"pairs\": [[0, 1]], \"length\": 0 }] }", "objects[1].length = 0: must be a positive number (m)" },
        { "rod between coincident particles", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[0, 1, 0], [0, 1, 0]] }, { \"type\": \"rods\", \"pairs\": [[0, 1]] }] }", "objects[1].pairs[0]: the particles start 0 m apart, and a rod needs a positive length" },
        { "cable beyond the particles", "{ \"objects\": [{ \"type\": \"cables\", \"pairs\": [[0, 1]], \"length\": 1 }] }", "names a particle, and the scene has none" },
        { "load without force", "{ \"objects\": [{ \"type\": \"load\", \"particles\": [0] }] }", "objects[0]: a load object needs \"force\"" },
        { "load on no particle", "{ \"objects\": [{ \"type\": \"load\", \"particles\": [3], \"force\": [1, 0, 0] }] }", "objects[0].particles[0] = 3: names a particle" },
        { "negative dt", "{ \"dt\": -0.01 }", "scene.json:1:9: dt = -0.01: must be a positive number (s)" },
        { "zero duration", "{ \"duration\": 0 }", "duration = 0: must be a positive number (s)" },
        { "negative drag", "{ \"drag\": -1 }", "drag = -1: must be a number >= 0 (N s/m)" },
        { "gravity of two", "{ \"gravity\": [0, -9.81] }", "gravity = [0, -9.81]: must be [x, y, z]" },
        { "unknown integrator", "{ \"integrator\": \"rk5\" }", "integrator = \"rk5\": is not an integrator (did you mean 'rk4'?)" },
        { "integrator number", "{ \"integrator\": 4 }", "integrator = 4: must be a name" },
        { "integrator without name", "{ \"integrator\": { \"substeps\": 4 } }", "the integrator needs \"name\"" },
        { "fractional substeps", "{ \"integrator\": { \"name\": \"xpbd\", \"substeps\": 2.5 } }", "integrator.substeps = 2.5: must be a whole number from 1 to 1000" },
        { "too many substeps", "{ \"integrator\": { \"name\": \"xpbd\", \"substeps\": 5000 } }", "must be a whole number from 1 to 1000" },
        { "tiny tolerance", "{ \"integrator\": { \"name\": \"rk45\", \"tolerance\": 1e-20 } }", "integrator.tolerance = 1E-20: must be at least" },
        { "typo in integrator", "{ \"integrator\": { \"name\": \"xpbd\", \"substep\": 4 } }", "integrator.substep: unknown key for the integrator (did you mean 'substeps'?)" },
        { "particle collisions number", "{ \"particleCollisions\": 1 }", "particleCollisions = 1: must be true, false, or" },
        { "restitution above 1", "{ \"particleCollisions\": { \"restitution\": 1.5 } }", "particleCollisions.restitution = 1.5: must be a number from 0 to 1" },
        { "plane without normal", "{ \"colliders\": [{ \"type\": \"plane\", \"point\": [0, 0, 0] }] }", "colliders[0]: a plane collider needs \"normal\"" },
        { "plane with zero normal", "{ \"colliders\": [{ \"type\": \"plane\", \"point\": [0, 0, 0], \"normal\": [0, 0, 0] }] }", "colliders[0].normal = [0, 0, 0]: must not be [0, 0, 0]" },
        { "sphere of zero radius", "{ \"colliders\": [{ \"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 0 }] }", "colliders[0].radius = 0: must be a positive number (m)" },
        { "capsule without radius", "{ \"colliders\": [{ \"type\": \"capsule\", \"a\": [0, 0, 0], \"b\": [0, 1, 0] }] }", "colliders[0]: a capsule collider needs \"radius\": a positive number (m)" },
        { "box with a flat side", "{ \"colliders\": [{ \"type\": \"box\", \"center\": [0, 0, 0], \"halfExtents\": [1, 0, 1] }] }", "colliders[0].halfExtents = [1, 0, 1]: must be three positive numbers" },
        { "box rotation not unit", "{ \"colliders\": [{ \"type\": \"box\", \"center\": [0, 0, 0], \"halfExtents\": [1, 1, 1], \"rotation\": [1, 1, 0, 0] }] }", "rotation = [1, 1, 0, 0]: must be a unit quaternion [w, x, y, z]; its length is 1.41421" },
        { "restitution of a collider", "{ \"colliders\": [{ \"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1, \"restitution\": -0.5 }] }", "colliders[0].restitution = -0.5: must be a number from 0 to 1" },
        { "friction of a collider", "{ \"colliders\": [{ \"type\": \"sphere\", \"center\": [0, 0, 0], \"radius\": 1, \"friction\": -1 }] }", "friction = -1: must be a number >= 0" },
        { "typo in a collider", "{ \"colliders\": [{ \"type\": \"sphere\", \"centre\": [0, 0, 0], \"radius\": 1 }] }", "colliders[0]: a sphere collider needs \"center\"" },
        { "a long string", "{ \"objects\": [{ \"type\": \"" + new string('x', 70_000) + "\" }] }", "a string longer than 65,536 characters" },
        { "far apart spring ends", "{ \"objects\": [{ \"type\": \"particles\", \"positions\": [[-1e308, 0, 0], [1e308, 0, 0]] }, { \"type\": \"springs\", \"pairs\": [[0, 1]], \"stiffness\": 1 }] }", "objects[1].pairs[0]: the particles are too far apart at the start for a length to be finite" },
    };

    [Theory]
    [MemberData(nameof(Corpus))]
    public void A_bad_file_is_refused_with_one_line_naming_where_and_why(string name, string text, string expected)
    {
        var folder = Directory.CreateTempSubdirectory("scene-corpus-");
        try
        {
            var path = Path.Combine(folder.FullName, "scene.json");
            File.WriteAllText(path, text);
            var result = DemoProcess.Run("scene", path);
            Assert.True(result.ExitCode == 2, $"{name}: exit {result.ExitCode}; {result.Error}");
            Assert.Equal(string.Empty, result.Output);
            var line = Assert.Single(result.ErrorLines);
            Assert.StartsWith("error: " + path, line, StringComparison.Ordinal);
            var message = line.Substring(("error: " + folder.FullName + "/").Length);
            Assert.True(message.Contains(expected, StringComparison.Ordinal), $"{name}: '{message}' does not contain '{expected}'");
        }
        finally
        {
            folder.Delete(recursive: true);
        }
    }

    [Fact]
    public void A_file_too_large_is_refused_before_it_is_read()
    {
        var path = Path.Combine(Path.GetTempPath(), $"huge-{Guid.NewGuid():N}.json");
        using (var stream = new FileStream(path, FileMode.CreateNew))
        {
            stream.SetLength(100L << 20); // 100 MB of zero bytes, without writing them
        }

        try
        {
            var before = GC.GetAllocatedBytesForCurrentThread();
            var result = DemoProcess.Run("scene", path);
            var allocated = GC.GetAllocatedBytesForCurrentThread() - before;
            Assert.Equal(2, result.ExitCode);
            Assert.Contains("the file holds 104,857,600 bytes; a scene file may hold at most 67,108,864", Assert.Single(result.ErrorLines), StringComparison.Ordinal);
            Assert.True(allocated < 16 << 20, $"{allocated} bytes allocated");
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void A_large_file_of_valid_json_nonsense_is_refused_within_bounded_memory() => LargeNonsense("numbers", "1, ");

    [Theory]
    [Trait("Category", "Long")]
    [InlineData("vectors", "[1, 2, 3], ")]
    [InlineData("objects", "{\"a\": 1}, ")]
    public void Large_files_of_other_valid_json_nonsense_are_refused_within_bounded_memory(string name, string item) => LargeNonsense(name, item);

    private static void LargeNonsense(string name, string item)
    {
        // 60 MB of one huge array: under the size limit, over the count of values; the parser stops at 2^22 values, so the
        // allocations stay near 25 bytes per value (about 100 MB for the entries, doubled while they grow), never gigabytes.
        var path = Path.Combine(Path.GetTempPath(), $"nonsense-{name}-{Guid.NewGuid():N}.json");
        using (var writer = new StreamWriter(path))
        {
            writer.Write("{ \"objects\": [");
            var chunk = string.Concat(Enumerable.Repeat(item, (1 << 20) / item.Length));
            for (var megabytes = 0; megabytes < 60; megabytes++)
            {
                writer.Write(chunk);
            }

            writer.Write("1] }");
        }

        try
        {
            var before = GC.GetAllocatedBytesForCurrentThread();
            var result = DemoProcess.Run("scene", path);
            var allocated = GC.GetAllocatedBytesForCurrentThread() - before;
            Assert.Equal(2, result.ExitCode);
            Assert.Contains("more than 4,194,304 JSON values", Assert.Single(result.ErrorLines), StringComparison.Ordinal);
            Assert.True(allocated < 600L << 20, $"{allocated >> 20} MB allocated");
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void A_missing_file_is_refused_with_its_name()
    {
        var result = DemoProcess.Run("scene", "no-such-scene.json");
        Assert.Equal(2, result.ExitCode);
        Assert.Equal(string.Empty, result.Output);
        Assert.StartsWith("error: no-such-scene.json: cannot be read: ", Assert.Single(result.ErrorLines), StringComparison.Ordinal);
    }

    [Fact]
    public void Thousands_of_mutated_samples_are_each_refused_in_one_line_or_loaded_and_run()
    {
        var outcomes = Mutate(3000, seed: 20261203);
        _output.WriteLine($"3000 mutations: {outcomes.Refused} refused in one line, {outcomes.Ran} loaded and ran");
        Assert.True(outcomes.Refused > 500 && outcomes.Ran > 500, $"{outcomes.Refused} refused, {outcomes.Ran} ran: the mutations should exercise both");
    }

    [Fact]
    [Trait("Category", "Long")]
    public void Many_more_mutated_samples_are_each_refused_in_one_line_or_loaded_and_run()
    {
        var outcomes = Mutate(60_000, seed: 7);
        _output.WriteLine($"60000 mutations: {outcomes.Refused} refused in one line, {outcomes.Ran} loaded and ran");
        Assert.True(outcomes.Refused > 10_000 && outcomes.Ran > 10_000, $"{outcomes.Refused} refused, {outcomes.Ran} ran");
    }

    [Fact]
    public void A_sample_of_mutated_files_goes_through_the_command_as_one_error_line_or_a_run()
    {
        // The command's side of the same contract: exit 2 with exactly one line and nothing on stdout, or a run.
        var samples = SampleTexts();
        var random = new Random(99);
        var folder = Directory.CreateTempSubdirectory("scene-mutants-");
        try
        {
            for (var k = 0; k < 150; k++)
            {
                var (name, text) = samples[random.Next(samples.Count)];
                var path = Path.Combine(folder.FullName, $"{k}-{name}");
                File.WriteAllText(path, Mutation(text, random));
                var result = DemoProcess.Run("scene", path, "--duration", "0.01", "--dt", "0.005", "--format", "csv");
                if (result.ExitCode == 2)
                {
                    Assert.Equal(string.Empty, result.Output);
                    Assert.StartsWith("error: " + path, Assert.Single(result.ErrorLines), StringComparison.Ordinal);
                }
                else
                {
                    Assert.True(result.ExitCode is 0 or 3, $"exit {result.ExitCode}: {result.Error}");
                }
            }
        }
        finally
        {
            folder.Delete(recursive: true);
        }
    }

    private static (int Refused, int Ran) Mutate(int count, int seed)
    {
        var samples = SampleTexts();
        var random = new Random(seed);
        int refused = 0, ran = 0;
        for (var k = 0; k < count; k++)
        {
            var (name, text) = samples[random.Next(samples.Count)];
            var mutant = Mutation(text, random);
            Scene scene;
            try
            {
                scene = Scene.Parse(mutant, name);
            }
            catch (SceneException e)
            {
                Assert.StartsWith(name + ":", e.Message, StringComparison.Ordinal);
                Assert.DoesNotContain('\n', e.Message);
                refused++;
                continue;
            }

            try
            {
                var world = scene.Build();
                var integrator = IntegratorCatalog.Create(scene.Settings.Integrator, scene.Settings.Tolerance, Math.Min(scene.Settings.Substeps, 4));
                for (var step = 0; step < 2; step++)
                {
                    world.Step(integrator, 0.002);
                }

                ran++;
            }
            catch (SceneException e)
            {
                Assert.StartsWith(name + ":", e.Message, StringComparison.Ordinal);
                refused++;
            }
            catch (Exception e) when (e is SimulationDivergedException or SolverNotConvergedException)
            {
                ran++; // a run that diverges is a run (exit code 3), not a bad file
            }
        }

        return (refused, ran);
    }

    private static List<(string Name, string Text)> SampleTexts() =>
        Directory.GetFiles(_folder, "*.json").OrderBy(f => f, StringComparer.Ordinal)
            .Where(f => new FileInfo(f).Length < 40_000) // the cloth and the drape: mutations of their long lists say nothing more
            .Where(f => !File.ReadAllText(f).Contains(".obj\"", StringComparison.Ordinal)) // OBJ files beside them: mutants are parsed without their folder
            .Select(f => (Path.GetFileName(f), File.ReadAllText(f))).ToList();

    // One deterministic change of the kind a person or a broken tool makes: a character dropped, doubled or replaced, a
    // number changed to an awkward value, a line dropped or repeated, the text cut short, two values swapped.
    private static string Mutation(string text, Random random)
    {
        var at = random.Next(text.Length);
        switch (random.Next(9))
        {
            case 0:
                return text.Remove(at, 1);
            case 1:
                return text.Insert(at, text[at].ToString());
            case 2:
                const string noise = "{}[],:\"-.0123456789eE/ \ntfnxa\\'";
                return text.Remove(at, 1).Insert(at, noise[random.Next(noise.Length)].ToString());
            case 3:
                {
                    var digits = text.IndexOfAny("0123456789".ToCharArray(), at);
                    if (digits < 0)
                    {
                        return text;
                    }

                    var end = digits;
                    while (end < text.Length && "0123456789.eE-".Contains(text[end], StringComparison.Ordinal))
                    {
                        end++;
                    }

                    string[] awkward = { "-1", "0", "-0", "1e308", "-1e308", "1e-320", "2.5", "1000000", "4194304", "1.7976931348623157e308", "0.0000001", "99999999999" };
                    return text.Remove(digits, end - digits).Insert(digits, awkward[random.Next(awkward.Length)]);
                }

            case 4:
                {
                    var lines = text.Split('\n').ToList();
                    lines.RemoveAt(random.Next(lines.Count));
                    return string.Join('\n', lines);
                }

            case 5:
                {
                    var lines = text.Split('\n').ToList();
                    var line = random.Next(lines.Count);
                    lines.Insert(line, lines[line]);
                    return string.Join('\n', lines);
                }

            case 6:
                return text.Substring(0, at);
            case 7:
                {
                    string[] keys = { "\"type\"", "\"positions\"", "\"pairs\"", "\"pinned\"", "\"mass\"", "\"radius\"", "\"length\"", "\"stiffness\"", "\"particles\"", "\"rods\"", "\"springs\"", "\"plane\"" };
                    var key = keys[random.Next(keys.Length)];
                    var found = text.IndexOf(key, at, StringComparison.Ordinal);
                    return found < 0 ? text : text.Remove(found, key.Length).Insert(found, keys[random.Next(keys.Length)]);
                }

            default:
                {
                    var b = random.Next(text.Length);
                    var chars = text.ToCharArray();
                    (chars[at], chars[b]) = (chars[b], chars[at]);
                    return new string(chars);
                }
        }
    }
}
