#!/usr/bin/env python3
"""Large scenes for hierarchical radiosity's scaling ladder (docs/hierarchical.md): a terrain of
about N triangles (the terrain room's heightfield, finer), with boxes standing on it and a square
area light above. Files can be large (1 M triangles: 40 MB of OFF, 19 MB of binary PLY), so they
are written where you say, not into data/.

    python3 data/tools/make_terrain_ladder.py OUTDIR --triangles 1000000 [--format off|ply]
writes OUTDIR/terrain-<N>.off (or .ply) and OUTDIR/terrain-<N>.json."""
import argparse
import json
import math
import os

from terrain import write_terrain_off, write_terrain_ply

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("outdir")
parser.add_argument("--triangles", type=int, default=1000000, help="about this many terrain triangles")
parser.add_argument("--format", choices=["off", "ply"], default="off",
                    help="mesh file: ASCII OFF (default) or binary little-endian PLY (smaller, read faster)")
args = parser.parse_args()

n = max(4, int(round(math.sqrt(args.triangles / 2))))
size = 10.0
os.makedirs(args.outdir, exist_ok=True)
name = "terrain-%d" % (2 * n * n)
mesh = os.path.join(args.outdir, name + "." + args.format)
if args.format == "ply":
    write_terrain_ply(mesh, n, size, "%.9g")
else:
    write_terrain_off(mesh, n, size, "%.9g")

def box(x0, y0, z0, sx, sy, sz):
    """Five outward faces of a box standing at height z0 (no bottom)."""
    x1, y1, z1 = x0 + sx, y0 + sy, z0 + sz
    return [
        [[x0, y0, z1], [x1, y0, z1], [x1, y1, z1], [x0, y1, z1]],
        [[x0, y0, z0], [x1, y0, z0], [x1, y0, z1], [x0, y0, z1]],
        [[x1, y1, z0], [x0, y1, z0], [x0, y1, z1], [x1, y1, z1]],
        [[x0, y1, z0], [x0, y0, z0], [x0, y0, z1], [x0, y1, z1]],
        [[x1, y0, z0], [x1, y1, z0], [x1, y1, z1], [x1, y0, z1]],
    ]


# A heightfield cannot cross itself: its self-intersection check (the costliest load check, about
# 3 s a million triangles) is skipped (docs/formats.md).
surfaces = [{"name": "terrain", "material": "ground", "mesh": os.path.basename(mesh),
             "check_self_intersections": False}]
for k, (x, y) in enumerate([(2, 2), (7, 2.5), (3, 7), (7.5, 7)]):
    for f, face in enumerate(box(x, y, 0.6, 0.8, 0.8, 1.2)):
        surfaces.append({"name": "box %d face %d" % (k, f), "material": "stone", "polygon": face})
surfaces.append({"name": "lamp", "material": "lamp", "polygon": [[4, 4, 4], [4, 6, 4], [6, 6, 4], [6, 4, 4]]})
scene = {
    "name": name,
    "description": "%d-triangle terrain with four boxes under a square area light 4 m up (scaling ladder)." % (2 * n * n),
    "units": "m",
    "materials": {"ground": {"reflectance": [0.45, 0.4, 0.3]}, "stone": {"reflectance": [0.6, 0.6, 0.6]},
                  "lamp": {"reflectance": [0, 0, 0], "emission": [50, 50, 50]}},
    "surfaces": surfaces,
    "camera": {"position": [5, -6, 6], "look_at": [5, 5, 0], "up": [0, 0, 1], "fov_deg": 50},
}
with open(os.path.join(args.outdir, name + ".json"), "w") as out:
    json.dump(scene, out, indent=1)
print(os.path.join(args.outdir, name + ".json"))
