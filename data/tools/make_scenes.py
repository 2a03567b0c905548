#!/usr/bin/env python3
"""Writes radkit's generated data scenes: the Cornell boxes from the measured data
(docs/oracles.md, "CornellBox-Original" RGB set), small analytic scenes, an
icosphere interior and a 51 200-triangle terrain room for scaling work. Run from data/."""
import json, math

from terrain import write_terrain_off

def dump(name, scene):
    with open(name, "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")

def quad(a, b, c, d):
    return [list(a), list(b), list(c), list(d)]

# ---- Cornell box (mm). Vertex order is the measured data's; every face is CCW seen from inside.
H = 548.8
hole_x, hole_z = [0.0, 213.0, 343.0, 556.0], [0.0, 227.0, 332.0, 559.2]
ceiling = []
for i in range(3):
    for j in range(3):
        if i == 1 and j == 1:
            continue  # the light's hole
        xa, xb, za, zb = hole_x[i], hole_x[i + 1], hole_z[j], hole_z[j + 1]
        ceiling.append(quad((xb, H, za), (xb, H, zb), (xa, H, zb), (xa, H, za)))

short_block = [
    quad((130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)),
    quad((290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)),
    quad((130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)),
    quad((82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)),
    quad((240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)),
]
tall_block = [
    quad((423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0), (472.0, 330.0, 406.0)),
    quad((423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)),
    quad((472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)),
    quad((314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)),
    quad((265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)),
]

def cornell(name, blocks):
    surfaces = [
        {"name": "floor", "material": "white",
         "polygon": quad((552.8, 0, 0), (0, 0, 0), (0, 0, 559.2), (549.6, 0, 559.2))},
        {"name": "ceiling", "material": "white", "polygons": ceiling},
        {"name": "back wall", "material": "white",
         "polygon": quad((549.6, 0, 559.2), (0, 0, 559.2), (0, H, 559.2), (556.0, H, 559.2))},
        {"name": "right wall", "material": "green",
         "polygon": quad((0, 0, 559.2), (0, 0, 0), (0, H, 0), (0, H, 559.2))},
        {"name": "left wall", "material": "red",
         "polygon": quad((552.8, 0, 0), (549.6, 0, 559.2), (556.0, H, 559.2), (556.0, H, 0))},
        {"name": "light", "material": "light",
         "polygon": quad((343.0, H, 227.0), (343.0, H, 332.0), (213.0, H, 332.0), (213.0, H, 227.0))},
    ]
    if blocks:
        surfaces += [{"name": "short block", "material": "white", "polygons": short_block},
                     {"name": "tall block", "material": "white", "polygons": tall_block}]
    return {
        "name": name,
        "description": "Cornell box as measured (Cornell Program of Computer Graphics), "
                       "CornellBox-Original RGB set. The ceiling has the light's hole cut out; "
                       "the light lies in the ceiling plane. The left (red) wall is non-planar "
                       "as measured and is split into triangles on load.",
        "units": "mm",
        "materials": {
            "white": {"reflectance": [0.725, 0.71, 0.68]},
            "red": {"reflectance": [0.63, 0.065, 0.05]},
            "green": {"reflectance": [0.14, 0.45, 0.091]},
            "light": {"reflectance": [0.78, 0.78, 0.78], "emission": [17, 12, 4]},
        },
        "surfaces": surfaces,
        "camera": {"position": [278, 273, -800], "look_at": [278, 273, 0], "up": [0, 1, 0],
                   "fov_deg": 39.3077},
    }

dump("cornell-box.json", cornell("cornell-box", True))
dump("cornell-box-empty.json", cornell("cornell-box-empty", False))

# ---- Unit cube seen from inside: each face counter-clockwise seen from the centre.
def cube_faces():
    return {
        "bottom": quad((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)),
        "top": quad((0, 0, 1), (0, 1, 1), (1, 1, 1), (1, 0, 1)),
        "front": quad((0, 0, 0), (0, 0, 1), (1, 0, 1), (1, 0, 0)),
        "back": quad((0, 1, 0), (1, 1, 0), (1, 1, 1), (0, 1, 1)),
        "left": quad((0, 0, 0), (0, 1, 0), (0, 1, 1), (0, 0, 1)),
        "right": quad((1, 0, 0), (1, 0, 1), (1, 1, 1), (1, 1, 0)),
    }

dump("cube-one-emitter.json", {
    "name": "cube-one-emitter",
    "description": "Closed unit cube, inward normals; the top face emits. Reflectance 0.5 everywhere.",
    "units": "m",
    "materials": {"grey": {"reflectance": [0.5, 0.5, 0.5]},
                  "lamp": {"reflectance": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
    "surfaces": [{"name": n, "material": "lamp" if n == "top" else "grey", "polygon": p}
                 for n, p in cube_faces().items()],
    "camera": {"position": [0.5, -0.9, 0.5], "look_at": [0.5, 0.5, 0.5], "up": [0, 0, 1], "fov_deg": 60},
})
dump("furnace.json", {
    "name": "furnace",
    "description": "Closed unit cube, every face emitting 1 W/m² with reflectance 0.5: B = E/(1-rho) = 2.",
    "units": "m",
    "materials": {"glow": {"reflectance": [0.5, 0.5, 0.5], "emission": [1, 1, 1]}},
    "surfaces": [{"name": n, "material": "glow", "polygon": p} for n, p in cube_faces().items()],
})
dump("parallel-squares.json", {
    "name": "parallel-squares",
    "description": "Unit squares one apart, facing each other (Howell C-11, X = Y = 1: F = 0.19982489569838746).",
    "units": "m",
    "materials": {"grey": {"reflectance": [0.5, 0.5, 0.5]},
                  "lamp": {"reflectance": [0, 0, 0], "emission": [1, 1, 1]}},
    "surfaces": [
        {"name": "lower", "material": "grey", "polygon": quad((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0))},
        {"name": "upper", "material": "lamp", "polygon": quad((0, 0, 1), (0, 1, 1), (1, 1, 1), (1, 0, 1))},
    ],
})
dump("perpendicular-squares.json", {
    "name": "perpendicular-squares",
    "description": "Unit squares sharing an edge at a right angle (Howell C-14, W = H = 1: F = 0.20004377607540316).",
    "units": "m",
    "materials": {"grey": {"reflectance": [0.5, 0.5, 0.5]},
                  "lamp": {"reflectance": [0, 0, 0], "emission": [1, 1, 1]}},
    "surfaces": [
        {"name": "floor", "material": "grey", "polygon": quad((0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0))},
        {"name": "wall", "material": "lamp", "polygon": quad((0, 0, 0), (0, 0, 1), (1, 0, 1), (1, 0, 0))},
    ],
})

# ---- Icosphere interior: unit radius, faces wound clockwise from outside (normals inward).
def icosphere(levels):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
         (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
         (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        mid = {}
        def m(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                p = [(x + y) / 2 for x, y in zip(v[a], v[b])]
                r = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / r for x in p))
                mid[key] = len(v) - 1
            return mid[key]
        f = [g for a, b, c in f for g in ((a, m(a, b), m(c, a)), (b, m(b, c), m(a, b)),
                                          (c, m(c, a), m(b, c)), (m(a, b), m(b, c), m(c, a)))]
    return v, f

v, f = icosphere(2)
with open("sphere-interior.off", "w") as out:
    out.write("OFF\n%d %d 0\n" % (len(v), len(f)))
    for p in v:
        out.write("%.17g %.17g %.17g\n" % p)
    for a, b, c in f:
        out.write("3 %d %d %d\n" % (a, c, b))  # reversed: normals point inward
dump("sphere-interior.json", {
    "name": "sphere-interior",
    "description": "Inside of a unit icosphere (320 triangles, inward normals), emitting uniformly: "
                   "a spherical furnace, B = E/(1 - rho). For a true sphere F_ij = A_j / A.",
    "units": "m",
    "materials": {"grey": {"reflectance": [0.7, 0.7, 0.7], "emission": [1, 1, 1]}},
    "surfaces": [{"name": "sphere", "material": "grey", "mesh": "sphere-interior.off"}],
})

# ---- Terrain room: a 160×160 heightfield (51 200 triangles) under an area light, for scaling.
write_terrain_off("terrain-51k.off", 160)
dump("terrain-room.json", {
    "name": "terrain-room",
    "description": "51 200-triangle terrain (terrain-51k.off) lit by a square area light 4 m above it.",
    "units": "m",
    "materials": {"ground": {"reflectance": [0.45, 0.4, 0.3]},
                  "lamp": {"reflectance": [0, 0, 0], "emission": [50, 50, 50]}},
    "surfaces": [
        {"name": "terrain", "material": "ground", "mesh": "terrain-51k.off"},
        {"name": "lamp", "material": "lamp", "polygon": quad((4, 4, 4), (4, 6, 4), (6, 6, 4), (6, 4, 4))},
    ],
    "camera": {"position": [5, -6, 6], "look_at": [5, 5, 0], "up": [0, 0, 1], "fov_deg": 50},
})
