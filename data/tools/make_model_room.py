#!/usr/bin/env python3
"""Writes a closed room scene around a real model: a 4 x 4 x 3 m room (y up, inward faces,
a red and a green wall) lit by a 1 m² ceiling lamp emitting 10 W/m², with the model scaled to
--size metres (largest side) standing on the floor's centre.

    python3 data/tools/make_model_room.py MODEL.obj|.ply|.off|.stl --out scene.json
        [--size 1.2] [--model-reflectance 0.7] [--lift 0] [--open-wall] [--name NAME] [--up z]

The model's path is written relative to the scene file. Its coordinates (OBJ, OFF, ASCII or
binary PLY, ASCII or binary STL) are read here only to fit it (bounding box); radkit itself
loads the mesh. --up z stands a z-up model (most CAD and scan tools) upright."""
import argparse
import json
import os
import struct
import sys


PLY_TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
             "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
             "float": "f", "float32": "f", "double": "d", "float64": "d"}

# The model's up axis onto radkit's +y, as radkit's "transform": {"up": ...} turns it.
UP = {"y": lambda p: p, "z": lambda p: [p[0], p[2], -p[1]], "-z": lambda p: [p[0], -p[2], p[1]],
      "x": lambda p: [-p[1], p[0], p[2]]}


def ply_points(path, data):
    """Vertices and face count of an ASCII or binary PLY (vertices must be its first element)."""
    end = data.find(b"end_header")
    if end < 0:
        sys.exit(f"make_model_room.py: {path}: no end_header in its PLY header")
    header = data[:end].decode("ascii", "replace").splitlines()
    body = data[data.index(b"\n", end) + 1:]
    fmt = next((l.split()[1] for l in header if l.startswith("format")), "")
    elements, faces = [], 0
    for line in header:
        t = line.split()
        if t[:1] == ["element"]:
            elements.append((t[1], int(t[2]), []))
            if t[1] in ("face", "tristrips"):
                faces += int(t[2])
        elif t[:1] == ["property"] and elements:
            elements[-1][2].append(t[1:])
    if not elements or elements[0][0] != "vertex":
        sys.exit(f"make_model_room.py: {path}: the vertex element must come first in the header")
    _, nv, props = elements[0]
    names = [p[-1] for p in props]
    if any(p[0] == "list" for p in props) or not all(k in names for k in "xyz"):
        sys.exit(f"make_model_room.py: {path}: its vertices need scalar x, y and z properties")
    xyz = [names.index(k) for k in "xyz"]
    if fmt == "ascii":
        rows = body.decode("ascii", "replace").split("\n")[:nv]
        pts = [[float(r.split()[i]) for i in xyz] for r in rows]
    elif fmt in ("binary_little_endian", "binary_big_endian"):
        row = struct.Struct(("<" if fmt.endswith("little_endian") else ">") +
                            "".join(PLY_TYPES[p[0]] for p in props))
        pts = [[v[i] for i in xyz] for v in (row.unpack_from(body, k * row.size) for k in range(nv))]
    else:
        sys.exit(f"make_model_room.py: {path}: unknown PLY format '{fmt}'")
    return pts, faces


def bounds(path, up="y"):
    """The bounding box of the model turned so that `up` is +y, and fails on a mesh without
    faces (a point cloud), which radkit would refuse after the room is written."""
    ext = os.path.splitext(path)[1].lower()
    pts, faces = [], 0
    with open(path, "rb") as f:
        data = f.read()
    if ext == ".obj":
        for line in data.decode("utf-8", "replace").splitlines():
            if line.startswith("v "):
                pts.append([float(t) for t in line.split()[1:4]])
            elif line.startswith("f "):
                faces += 1
    elif ext == ".off":
        toks = [t for line in data.decode().splitlines() for t in line.split("#")[0].split()]
        at = 1 if toks[0].upper().endswith("OFF") and len(toks[0]) <= 4 else 0
        n, faces = int(toks[at]), int(toks[at + 1])
        pts = [[float(t) for t in toks[at + 3 + 3 * i: at + 6 + 3 * i]] for i in range(n)]
    elif ext == ".stl" and data[:5] == b"solid" and b"facet" in data[:1000]:
        for line in data.decode("utf-8", "replace").splitlines():
            t = line.split()
            if t[:1] == ["vertex"]:
                pts.append([float(v) for v in t[1:4]])
            elif t[:1] == ["facet"]:
                faces += 1
    elif ext == ".stl":
        faces = struct.unpack_from("<I", data, 80)[0]
        for i in range(faces):
            v = struct.unpack_from("<12f", data, 84 + 50 * i)
            pts += [v[3:6], v[6:9], v[9:12]]
    elif ext == ".ply":
        pts, faces = ply_points(path, data)
    else:
        sys.exit(f"make_model_room.py: cannot read {path}: use OBJ, OFF, PLY or STL")
    if not pts or faces == 0:
        sys.exit(f"make_model_room.py: {path} has no faces ({len(pts)} vertices): a point cloud "
                 "is not a surface. Fix: mesh it first (e.g. Poisson reconstruction in MeshLab)")
    pts = [UP[up](p) for p in pts]
    lo = [min(p[k] for p in pts) for k in range(3)]
    hi = [max(p[k] for p in pts) for k in range(3)]
    return lo, hi


def quad(a, b, c, d):
    return [a, b, c, d]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("model")
    ap.add_argument("--out", required=True)
    ap.add_argument("--size", type=float, default=1.2)
    ap.add_argument("--model-reflectance", type=float, default=0.7)
    ap.add_argument("--lift", type=float, default=0.0, help="metres between floor and model")
    ap.add_argument("--open-wall", action="store_true", help="leave the front wall out")
    ap.add_argument("--name", default=None)
    ap.add_argument("--up", choices=sorted(UP), default="y",
                    help="the model's up axis (z for most CAD and scan tools); it stands upright")
    a = ap.parse_args()
    if not (0 < a.size < 2.9) or not (0 <= a.model_reflectance < 1) or not (0 <= a.lift < 1):
        sys.exit("make_model_room.py: --size in (0, 2.9), --model-reflectance in [0, 1), "
                 "--lift in [0, 1)")
    lo, hi = bounds(a.model, a.up)
    s = a.size / max(h - l for h, l in zip(hi, lo))
    # Centre over the floor's middle, bottom on the floor (y up).
    t = [2 - s * (lo[0] + hi[0]) / 2, a.lift - s * lo[1], 2 - s * (lo[2] + hi[2]) / 2]
    W, D, H = 4.0, 4.0, 3.0
    surfaces = [
        {"name": "floor", "material": "floor",
         "polygon": quad([0, 0, 0], [0, 0, D], [W, 0, D], [W, 0, 0])},
        # Eight quads around the lamp, so no vertex lies on another quad's edge.
        {"name": "ceiling", "material": "wall", "polygons": [
            quad([x0, H, z0], [x1, H, z0], [x1, H, z1], [x0, H, z1])
            for (x0, x1) in ((0, 1.5), (1.5, 2.5), (2.5, W)) for (z0, z1) in ((0, 1.5), (1.5, 2.5), (2.5, D))
            if (x0, z0) != (1.5, 1.5)]},
        {"name": "lamp", "material": "lamp",
         "polygon": quad([1.5, H, 1.5], [2.5, H, 1.5], [2.5, H, 2.5], [1.5, H, 2.5])},
        {"name": "red wall", "material": "red",
         "polygon": quad([0, 0, 0], [0, H, 0], [0, H, D], [0, 0, D])},
        {"name": "green wall", "material": "green",
         "polygon": quad([W, 0, 0], [W, 0, D], [W, H, D], [W, H, 0])},
        {"name": "back wall", "material": "wall",
         "polygon": quad([0, 0, 0], [W, 0, 0], [W, H, 0], [0, H, 0])},
    ]
    if not a.open_wall:
        surfaces.append({"name": "front wall", "material": "wall",
                         "polygon": quad([0, 0, D], [0, H, D], [W, H, D], [W, 0, D])})
    rel = os.path.relpath(os.path.abspath(a.model), os.path.dirname(os.path.abspath(a.out)))
    surfaces.append({"name": "model", "material": "model", "mesh": rel,
                     "transform": ({"up": a.up} if a.up != "y" else {}) | {"scale": s, "translate": t}})
    m = a.model_reflectance
    name = a.name or os.path.splitext(os.path.basename(a.model))[0] + "-room"
    scene = {
        "name": name,
        "description": f"{os.path.basename(a.model)} ({a.size} m) on the floor of a closed 4 x 4 x 3 m "
                       "room under a 1 m² ceiling lamp (data/tools/make_model_room.py)",
        "units": "m",
        "materials": {
            "wall": {"reflectance": [0.7, 0.7, 0.7]},
            "red": {"reflectance": [0.7, 0.15, 0.15]},
            "green": {"reflectance": [0.15, 0.7, 0.15]},
            "floor": {"reflectance": [0.45, 0.4, 0.35]},
            "model": {"reflectance": [m, m, m]},
            "lamp": {"reflectance": [0, 0, 0], "emission": [10, 10, 10]},
        },
        "surfaces": surfaces,
        "camera": {"position": [2, 1.5, 3.9], "look_at": [2, 0.6, 2], "up": [0, 1, 0],
                   "fov_deg": 60},
    }
    tmp = a.out + ".tmp"
    with open(tmp, "w") as f:
        json.dump(scene, f, indent=1)
    os.replace(tmp, a.out)


if __name__ == "__main__":
    main()
