#!/usr/bin/env python3
"""Writes the larger hand-made sample scenes of samples/scenes/ (the rope bridge, the ball pit), whose positions
are too many to type. The course's scenarios are written by tests/ParticlePhysics.Tests/Scenes/CourseSceneFiles.cs
instead, from the scenarios' own worlds. Run from the repository root: python3 tools/make-scene-samples.py"""
import json


def dump(path, comment, scene):
    def fmt(value, indent):
        # One line per list of numbers or of short lists, objects spread over lines.
        if isinstance(value, dict):
            inner = ",\n".join(" " * (indent + 2) + json.dumps(k) + ": " + fmt(v, indent + 2) for k, v in value.items())
            return "{\n" + inner + "\n" + " " * indent + "}"
        if isinstance(value, list) and value and isinstance(value[0], dict):
            return "[\n" + ",\n".join(" " * (indent + 2) + fmt(v, indent + 2) for v in value) + "\n" + " " * indent + "]"
        return json.dumps(value)
    with open(path, "w") as f:
        for line in comment:
            f.write("// " + line + "\n")
        f.write(fmt(scene, 0) + "\n")


def rope_bridge():
    n, span, width, slack = 21, 4.0, 0.6, 1.05
    step = span / (n - 1)
    ropes = [[round(-span / 2 + i * step, 12), 0.0, z] for z in (0.0, width) for i in range(n)]
    cables = [[i, i + 1] for i in range(n - 1)] + [[n + i, n + i + 1] for i in range(n - 1)]
    planks = [[i, n + i] for i in range(1, n - 1)]
    braces = [[i, n + i + 1] for i in range(n - 1)] + [[i + 1, n + i] for i in range(n - 1)]
    return {
        "integrator": {"name": "xpbd", "substeps": 20},
        "dt": 1 / 60,
        "duration": 6,
        "drag": 0.5,
        "objects": [
            {"type": "particles", "positions": ropes, "mass": 2, "pinned": [0, n - 1, n, 2 * n - 1]},
            {"type": "cables", "pairs": cables, "length": round(step * slack, 12)},
            {"type": "rods", "pairs": planks},
            {"type": "springs", "pairs": braces, "stiffness": 2000, "damping": 5},
            {"type": "load", "particles": [n // 2, n + n // 2], "force": [0, -343, 0]},
        ],
    }


def ball_pit():
    # 6 x 6 x 8 balls on a lattice of spacing 0.11 m, nudged by a fixed pattern so that they do not stack.
    r, spacing, side, layers = 0.05, 0.11, 6, 8
    seed = 12345
    positions = []
    for layer in range(layers):
        for row in range(side):
            for col in range(side):
                seed = (1103515245 * seed + 12345) % 2**31
                jx = (seed / 2**31 - 0.5) * 0.01
                seed = (1103515245 * seed + 12345) % 2**31
                jz = (seed / 2**31 - 0.5) * 0.01
                positions.append([round(-0.3 + spacing * (col + 0.5) + jx, 6), round(0.4 + spacing * layer, 6),
                                  round(-0.3 + spacing * (row + 0.5) + jz, 6)])
    wall = 0.05
    return {
        "integrator": {"name": "xpbd", "substeps": 10},
        "dt": 1 / 60,
        "duration": 4,
        "particleCollisions": {"restitution": 0.3, "friction": 0.2},
        "objects": [{"type": "particles", "positions": positions, "mass": 0.05, "radius": r}],
        "colliders": [
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "restitution": 0.3, "friction": 0.3},
            {"type": "box", "center": [-0.4 - wall, 0.4, 0], "halfExtents": [wall, 0.4, 0.45]},
            {"type": "box", "center": [0.4 + wall, 0.4, 0], "halfExtents": [wall, 0.4, 0.45]},
            {"type": "box", "center": [0, 0.4, -0.4 - wall], "halfExtents": [0.4, 0.4, wall]},
            {"type": "box", "center": [0, 0.4, 0.4 + wall], "halfExtents": [0.4, 0.4, wall]},
            {"type": "sphere", "center": [0, 0, 0], "radius": 0.15, "friction": 0.3},
        ],
    }


def icosphere(radius, subdivisions):
    # The icosahedron, each triangle split into four per level, new vertices pushed out to the sphere; wound
    # counter-clockwise seen from outside (as StandardMeshes.Icosphere in the library).
    t = (1 + 5 ** 0.5) / 2
    points = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
              (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    unit = lambda p: tuple(c / sum(x * x for x in p) ** 0.5 for c in p)
    points = [unit(p) for p in points]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
             (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
             (8, 6, 7), (9, 8, 1)]
    for _ in range(subdivisions):
        middles, next_faces = {}, []

        def middle(i, j):
            key = (min(i, j), max(i, j))
            if key not in middles:
                points.append(unit(tuple(a + b for a, b in zip(points[i], points[j]))))
                middles[key] = len(points) - 1
            return middles[key]
        for a, b, c in faces:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            next_faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = next_faces
    return [tuple(radius * c for c in p) for p in points], faces


def drape_and_slope():
    # A cloth of 16 x 16 cells of 5 cm dropped over a boulder (an OBJ mesh of 320 facets, radius 0.3 m, on the ground),
    # and six balls rolling down a terrain of 15 x 6 cells beside it that falls from 0.9 m to the ground.
    vertices, faces = icosphere(0.3, 2)
    with open("samples/scenes/boulder.obj", "w") as f:
        f.write("# A boulder: a geodesic sphere of radius 0.3 m, 320 facets. Written by tools/make-scene-samples.py.\n")
        for v in vertices:
            f.write("v %.9f %.9f %.9f\n" % v)
        for t in faces:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))
    n, h = 16, 0.05
    cloth = [[round(-n * h / 2 + j * h, 6), 0.9, round(-n * h / 2 + i * h, 6)] for i in range(n + 1) for j in range(n + 1)]
    cells = []
    for i in range(n):
        for j in range(n):
            v = i * (n + 1) + j
            cells += [[v, v + n + 1, v + 1], [v + 1, v + n + 1, v + n + 2]]
    rows, columns, dx = 7, 16, 0.2
    heights = [[round(0.9 * (1 - c / (columns - 1)) ** 2 + 0.03 * (r % 2), 6) for c in range(columns)] for r in range(rows)]
    balls = [[1.3, 1.2, round(-0.45 + 0.18 * k, 6)] for k in range(6)]
    return {
        "integrator": {"name": "xpbd", "substeps": 20},
        "dt": 1 / 60,
        "duration": 4,
        "objects": [
            {"type": "cloth", "mesh": {"vertices": cloth, "triangles": cells}, "density": 0.2,
             "stretch": {"modulus": 1000, "poisson": 0.3, "damping": 0.2}, "bending": {"rigidity": 0.0001},
             "thickness": 0.02},
            {"type": "particles", "positions": balls, "mass": 0.2, "radius": 0.05},
        ],
        "colliders": [
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5},
            {"type": "mesh", "mesh": {"obj": "boulder.obj"}, "position": [0, 0.3, 0], "friction": 0.5},
            {"type": "heightfield", "origin": [1.2, 0, -0.6], "cellSize": [dx, dx], "heights": heights, "friction": 0.1},
        ],
    }


def cloth_fold():
    # A cloth of 24 x 24 cells of 2.5 cm (60 cm square) dropped off-centre over a sphere of radius 15 cm on the ground:
    # it drapes and its sides fold onto themselves, kept 1 cm apart by self-collision.
    n, h = 24, 0.025
    cloth = [[round(-0.25 + j * h, 6), 0.4, round(-0.32 + i * h, 6)] for i in range(n + 1) for j in range(n + 1)]
    cells = []
    for i in range(n):
        for j in range(n):
            v = i * (n + 1) + j
            cells += [[v, v + n + 1, v + 1], [v + 1, v + n + 1, v + n + 2]]
    return {
        "integrator": {"name": "xpbd", "substeps": 10},
        "dt": 1 / 60,
        "duration": 4,
        "objects": [
            {"type": "cloth", "mesh": {"vertices": cloth, "triangles": cells}, "density": 0.2,
             "stretch": {"modulus": 1000, "poisson": 0.3}, "bending": {"rigidity": 0.00001},
             "thickness": 0.01, "selfCollision": True},
        ],
        "colliders": [
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5},
            {"type": "sphere", "center": [0, 0.15, 0], "radius": 0.15, "friction": 0.5},
        ],
    }


dump("samples/scenes/rope-bridge.json", [
    "A rope bridge: two ropes of 21 particles (2 kg each) joined by cables 5 % longer than their spacing, pinned at",
    "both ends 4 m apart; planks are rods across, diagonal springs brace it, and a 35 kg walker (343 N on each rope)",
    "stands in the middle. Written by tools/make-scene-samples.py."], rope_bridge())
dump("samples/scenes/ball-pit.json", [
    "A ball pit: 288 balls of radius 5 cm fall into a box of four walls on the ground, around a half-buried sphere;",
    "they collide with each other (restitution 0.3, friction 0.2). Written by tools/make-scene-samples.py."], ball_pit())


def flag():
    # A flag of 12 x 8 cells of 0.1 m in the plane z = 0, cut along x = 0.6 into two halves as a UV seam cuts a render
    # mesh: the seam's vertices are written twice, and "weld" merges them. Its pole edge x = 0 is pinned.
    cols, rows, h, seam = 12, 8, 0.1, 6
    vertices, index = [], {}
    for half, (c0, c1) in enumerate(((0, seam), (seam, cols))):
        for r in range(rows + 1):
            for c in range(c0, c1 + 1):
                index[(half, r, c)] = len(vertices)
                vertices.append((round(c * h, 6), round(1.5 - r * h, 6), 0.0))
    faces = []
    for half, (c0, c1) in enumerate(((0, seam), (seam, cols))):
        for r in range(rows):
            for c in range(c0, c1):
                a, b = index[(half, r, c)], index[(half, r, c + 1)]
                d, e = index[(half, r + 1, c)], index[(half, r + 1, c + 1)]
                faces += [(a, d, b), (b, d, e)]
    with open("samples/scenes/flag.obj", "w") as f:
        f.write("# A flag of 12 x 8 cells cut into two halves along x = 0.6 (a UV seam). Written by tools/make-scene-samples.py.\n")
        for v in vertices:
            f.write("v %g %g %g\n" % v)
        for t in faces:
            f.write("f %d %d %d\n" % tuple(i + 1 for i in t))
    pole = [index[(0, r, 0)] for r in range(rows + 1)]
    return {
        "integrator": {"name": "xpbd", "substeps": 20},
        "dt": 1 / 60,
        "duration": 4,
        "objects": [{
            "type": "cloth",
            "mesh": {"obj": "flag.obj"},
            "weld": True,
            "density": 0.2,
            "stretch": {"modulus": 1000, "poisson": 0.3, "damping": 0.2},
            "bending": {"rigidity": 0.0001},
            "pinned": pole,
            "thickness": 0.01,
        }],
        "colliders": [{"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0]}],
    }


def flag_in_wind():
    # The same flag (flag.obj) in a 5 m/s wind along +x with a gust: a wave across the flag (z) of 0.6 m/s at 0.7 Hz
    # and one along it of 1 m/s at 0.3 Hz, both travelling downwind. Flat in the plane of the wind, the flag would feel
    # no force until something breaks its symmetry: the gust does, and it streams out and flutters.
    scene = flag()
    scene["duration"] = 8
    scene["air"] = {
        "density": 1.2, "velocity": [5, 0, 0], "drag": 1.2, "lift": 0.5,
        "gust": [
            {"amplitude": [0, 0, 0.6], "frequency": 0.7, "waveVector": [0.9, 0, 0]},
            {"amplitude": [1, 0, 0], "frequency": 0.3, "waveVector": [0.4, 0, 0], "phase": 1},
        ],
    }
    scene["objects"][0]["aerodynamics"] = True
    return scene


def ropes():
    # Two ropes of 1 m and 21 points: one clamped horizontally at its first two points, with bending rigidity EI, sags
    # mu g L^4 / (8 EI) = 0.049 m (mu = 0.1 kg/m, EI = 2.5 N m^2, L from midway between the pinned points); one of
    # springs without bending hangs from both ends.
    n = 20
    stiff = [[round((i - 0.5) / (n - 0.5), 12), 1.0, 0.0] for i in range(n + 1)]
    limp = [[round(-1.2 + 1.0 * i / n, 12), 1.0, 0.5] for i in range(n + 1)]
    return {
        "integrator": {"name": "implicit-euler"},
        "dt": 0.02,
        "duration": 4,
        "drag": 0.01,
        "objects": [
            {"type": "rope", "points": stiff, "mass": 0.1 * n / (n - 0.5), "stretch": {"stiffness": 20000, "damping": 1},
             "bending": {"rigidity": 2.5}, "pinned": [0, 1]},
            {"type": "rope", "points": limp, "mass": 0.1, "stretch": {"stiffness": 2000, "damping": 0.5}, "pinned": [0, n]},
        ],
    }


def bodies():
    # Eleven boxes, rigid and soft, and a rigid boulder filled from boulder.obj, dropped from a fixed pattern of
    # places and turns into a tank of four walls on the ground.
    import math

    def turn(axis, degrees):
        n = math.sqrt(sum(a * a for a in axis))
        h = math.radians(degrees) / 2
        return [round(math.cos(h), 12)] + [round(math.sin(h) * a / n, 12) for a in axis]

    sizes = [[0.3, 0.2, 0.2], [0.2, 0.2, 0.2], [0.4, 0.1, 0.2], [0.25, 0.25, 0.15], [0.3, 0.15, 0.3], [0.2, 0.3, 0.1]]
    places = [[-0.3, 0.4, -0.25], [0.25, 0.55, 0.2], [0.0, 0.8, 0.0], [-0.2, 1.05, 0.25], [0.3, 1.3, -0.2],
              [-0.25, 1.55, -0.1], [0.1, 1.8, 0.3], [0.25, 2.05, 0.05], [-0.1, 2.3, -0.3], [0.0, 2.55, 0.15],
              [-0.3, 2.8, 0.1]]
    objects = []
    for k, centre in enumerate(places):
        soft = k % 3 == 2
        body = {"type": "soft" if soft else "rigid",
                "box": {"center": centre, "size": sizes[k % len(sizes)], "rotation": turn([1, 2 + k % 3, k % 2], 17 * k)},
                "spacing": 0.05, "density": 400 if soft else 600, "friction": 0.5, "restitution": 0.1}
        if soft:
            body["stiffness"] = 0.6
        objects.append(body)
    objects.append({"type": "rigid", "mesh": {"obj": "boulder.obj"}, "position": [0.05, 3.3, -0.05], "spacing": 0.075,
                    "density": 800, "friction": 0.5, "angularVelocity": [0, 0, 2]})
    # A column of sand poured last, off-centre: it slumps over the bodies into a pile against the tank's wall.
    objects.append({"type": "granular", "box": {"min": [0.2, 3.8, 0.2], "max": [0.44, 4.4, 0.44]}, "spacing": 0.04,
                    "density": 1600, "friction": 0.8, "rollingFriction": 0.3})
    wall = 0.05
    return {
        "integrator": {"name": "xpbd", "substeps": 10},
        "dt": 1 / 60,
        "duration": 8,
        "sleep": {"speed": 0.05},
        "objects": objects,
        "colliders": [
            {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "friction": 0.5},
            {"type": "box", "center": [-0.6 - wall, 0.4, 0], "halfExtents": [wall, 0.4, 0.65], "friction": 0.3},
            {"type": "box", "center": [0.6 + wall, 0.4, 0], "halfExtents": [wall, 0.4, 0.65], "friction": 0.3},
            {"type": "box", "center": [0, 0.4, -0.6 - wall], "halfExtents": [0.6, 0.4, wall], "friction": 0.3},
            {"type": "box", "center": [0, 0.4, 0.6 + wall], "halfExtents": [0.6, 0.4, wall], "friction": 0.3},
        ],
    }


dump("samples/scenes/flag.json", [
    "A flag from an OBJ mesh cut along a UV seam: welded into one cloth of membrane (Y = 1000 N/m, nu = 0.3) and",
    "plate bending (D = 1e-4 N m), pinned along its pole and hanging from it. Written by tools/make-scene-samples.py.",
], flag())
dump("samples/scenes/flag-in-wind.json", [
    "The flag of flag.json in a 5 m/s wind along +x with a deterministic gust (air density 1.2 kg/m^3, C_d 1.2, C_l 0.5):",
    "its triangles feel pressure drag and lift, and it streams out downwind and flutters. Written by tools/make-scene-samples.py.",
], flag_in_wind())
dump("samples/scenes/ropes.json", [
    "Two ropes of 1 m: one held out horizontally by its first two points, with bending rigidity EI = 2.5 N m^2, which",
    "sags 4.9 cm, and one of springs without bending hanging from both ends. Written by tools/make-scene-samples.py.",
], ropes())
dump("samples/scenes/drape-and-slope.json", [
    "A cloth of 16 x 16 cells dropped over a boulder given as an OBJ mesh (boulder.obj, 320 facets) and six balls sliding",
    "down a terrain (a height field) beside it. Written by tools/make-scene-samples.py."], drape_and_slope())
dump("samples/scenes/cloth-fold.json", [
    "A cloth of 24 x 24 cells dropped off-centre over a sphere: it drapes and folds onto itself, and self-collision",
    "(thickness 1 cm) keeps it from passing through itself. Written by tools/make-scene-samples.py."], cloth_fold())
dump("samples/scenes/bodies.json", [
    "Eleven boxes, eight rigid and three soft (shape matching of stiffness 0.6), and a rigid boulder filled from",
    "boulder.obj, dropped into a tank, then a column of 540 grains of sand (friction 0.8, rolling friction 0.3) poured",
    "over them: they land on each other, tumble and settle, and the sand runs into the gaps and piles against a wall;",
    "what stays below 5 cm/s for half a second falls asleep. Written by tools/make-scene-samples.py."], bodies())
