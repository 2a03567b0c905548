#!/usr/bin/env python3
"""Writes the two models docs/bring-your-own-model.md walks through, shaped like files users
bring (the scanned mesh is data/tools/make_scan.py's):

  OUT/bracket.stl              a CAD part as CAD tools export it: binary STL, millimetres, z up
                               (an L bracket 80 x 40 x 60 mm, 5 mm plate, closed)
  OUT/workshop.json            a light box 0.6 x 0.4 x 0.5 m (metres, y up) with the bracket
                               standing in it through "transform" {"up": "z", "scale": 0.001}
  OUT/textured-room/room.obj   a room as a modelling tool exports it: OBJ + MTL, y up, metres,
  OUT/textured-room/room.mtl   a ceiling lamp (Ke), plank flooring and a painting as map_Kd
  OUT/textured-room/textures/  PNG textures, a table; no camera (radkit picks one inside)

Usage: python3 data/tools/make_own_models.py OUT
"""
import argparse
import json
import os
import struct
import zlib


def write_png(path, width, height, pixel):
    """An 8-bit RGB PNG; pixel(x, y) gives (r, g, b) in 0..255, y from the top."""
    raw = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
                + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def bracket_triangles():
    """The L profile (x along the plate, z up, mm) extruded 40 mm along y, outward-wound."""
    profile = [(0, 0), (80, 0), (80, 5), (5, 5), (5, 60), (0, 60)]  # counter-clockwise in (x, z)
    depth = 40
    near = [(x, 0, z) for x, z in profile]
    far = [(x, depth, z) for x, z in profile]
    tris = []
    # Caps: a fan from the corner at the origin covers the L. Seen from −y, (x, z) counter-
    # clockwise is clockwise, so the near cap (normal −y) takes the profile as it is.
    for k in range(1, len(profile) - 1):
        tris.append((near[0], near[k], near[k + 1]))
        tris.append((far[0], far[k + 1], far[k]))
    for k in range(len(profile)):
        a, b = k, (k + 1) % len(profile)
        tris.append((near[a], far[a], far[b]))
        tris.append((near[a], far[b], near[b]))
    return tris


def signed_volume(tris):
    v = 0.0
    for a, b, c in tris:
        v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
              + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6
    return v


def write_stl(path, tris):
    with open(path, "wb") as f:
        f.write(b"L bracket, mm, z up (radkit data/tools/make_own_models.py)".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for a, b, c in tris:
            u = [b[i] - a[i] for i in range(3)]
            w = [c[i] - a[i] for i in range(3)]
            n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
            length = sum(x * x for x in n) ** 0.5
            f.write(struct.pack("<3f", *[x / length for x in n]))
            for p in (a, b, c):
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


def box_inside(x0, y0, z0, x1, y1, z1):
    """The six inner faces of a box (normals pointing in), as named quads."""
    return {
        "floor": [(x0, y0, z0), (x0, y0, z1), (x1, y0, z1), (x1, y0, z0)],
        "ceiling": [(x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1)],
        "west wall": [(x0, y0, z0), (x0, y1, z0), (x0, y1, z1), (x0, y0, z1)],
        "east wall": [(x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0)],
        "south wall": [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0)],
        "north wall": [(x0, y0, z1), (x0, y1, z1), (x1, y1, z1), (x1, y0, z1)],
    }


def ceiling_grid(xs, zs, y):
    """A ceiling at height y (facing down) cut by xs and zs into 3 x 3 cells without
    T-junctions: the eight around the middle (the ceiling) and the middle one (the lamp)."""
    cells = [[(xs[i], y, zs[j]), (xs[i + 1], y, zs[j]), (xs[i + 1], y, zs[j + 1]), (xs[i], y, zs[j + 1])]
             for j in range(3) for i in range(3)]
    return cells[:4] + cells[5:], cells[4]


def box_outside(x0, y0, z0, x1, y1, z1):
    """A closed box's faces wound outward (the inside faces reversed)."""
    return [list(reversed(q)) for q in box_inside(x0, y0, z0, x1, y1, z1).values()]


def workshop(out):
    tris = bracket_triangles()
    assert signed_volume(tris) > 0, "the bracket must be wound outward"
    write_stl(os.path.join(out, "bracket.stl"), tris)
    w, h, d = 0.6, 0.4, 0.5
    walls = box_inside(0, 0, 0, w, h, d)
    surfaces = [{"name": name, "material": "bench" if name == "floor" else "white",
                 "polygon": [list(p) for p in quad]} for name, quad in walls.items() if name != "ceiling"]
    ring, lamp = ceiling_grid([0, 0.2, 0.4, w], [0, 0.15, 0.35, d], h)
    surfaces.append({"name": "ceiling", "material": "white", "polygons": [[list(p) for p in q] for q in ring]})
    surfaces.append({"name": "lamp", "material": "lamp", "polygon": [list(p) for p in lamp]})
    # The STL's z is up and its unit mm: "up" turns (x, y, z) into (x, z, −y), then the scale
    # makes millimetres metres and the translation stands it mid-box (it spans z −0.04..0).
    surfaces.append({"name": "bracket", "material": "steel", "mesh": "bracket.stl",
                     "transform": {"up": "z", "scale": 0.001, "translate": [0.26, 0, 0.27]}})
    scene = {
        "description": "An L bracket from a CAD STL (mm, z up) in a 0.6 x 0.4 x 0.5 m light box.",
        "units": "m",
        "materials": {"white": {"reflectance": [0.8, 0.8, 0.8]},
                      "bench": {"reflectance": [0.45, 0.42, 0.38]},
                      "steel": {"reflectance": [0.55, 0.56, 0.58]},
                      "lamp": {"reflectance": [0, 0, 0], "emission": [40, 40, 40]}},
        "surfaces": surfaces,
        "camera": {"position": [0.4, 0.13, 0.42], "look_at": [0.29, 0.03, 0.25], "up": [0, 1, 0],
                   "fov_deg": 50},
    }
    with open(os.path.join(out, "workshop.json"), "w") as f:
        json.dump(scene, f, indent=1)
        f.write("\n")


def textured_room(out):
    room = os.path.join(out, "textured-room")
    os.makedirs(os.path.join(room, "textures"), exist_ok=True)
    # Planks: 8 boards across, two browns with a dark seam; mean linear colour about 0.2.
    write_png(os.path.join(room, "textures", "planks.png"), 64, 64,
              lambda x, y: (60, 40, 25) if x % 8 == 0 else ((168, 118, 72) if (x // 8 + y // 32) % 2 else (140, 95, 55)))
    # A painting: a blue sky over green hills and a yellow sun.
    def painting(x, y):
        if (x - 44) ** 2 + (y - 10) ** 2 < 36:
            return (250, 220, 60)
        return (70, 130, 200) if y < 20 + 4 * ((x // 8) % 2) else (60, 150, 70)
    write_png(os.path.join(room, "textures", "painting.png"), 64, 40, painting)
    with open(os.path.join(room, "room.mtl"), "w") as f:
        f.write("# radkit data/tools/make_own_models.py: a room as a modelling tool exports it\n"
                "newmtl plaster\nKd 0.72 0.70 0.66\n"
                "newmtl ceiling\nKd 0.82 0.82 0.82\n"
                "newmtl planks\nKd 0.5 0.35 0.2\nmap_Kd textures/planks.png\n"
                "newmtl painting\nKd 0.5 0.5 0.5\nmap_Kd textures/painting.png\n"
                "newmtl oak\nKd 0.35 0.24 0.14\n"
                "newmtl lamp\nKd 0 0 0\nKe 30 30 28\n")
    vertices, lines, index = [], [], {}

    def face(points):  # corners at one position share a vertex, as exporters write them
        ids = []
        for p in points:
            if p not in index:
                vertices.append(p)
                index[p] = len(vertices)
            ids.append(index[p])
        lines.append("f " + " ".join(map(str, ids)))

    W, H, D = 4.0, 2.8, 5.0
    walls = box_inside(0, 0, 0, W, H, D)
    for name, material in (("floor", "planks"), ("west wall", "plaster"), ("east wall", "plaster"),
                           ("south wall", "plaster"), ("north wall", "plaster")):
        lines.append("o %s\nusemtl %s" % (name.replace(" ", "_"), material))
        face(walls[name])
    # The lamp sits in a hole of the ceiling, as a recessed panel does.
    ring, lamp = ceiling_grid([0, 1.5, 2.5, W], [0, 2.0, 3.0, D], H)
    lines.append("o ceiling\nusemtl ceiling")
    for q in ring:
        face(q)
    lines.append("o lamp\nusemtl lamp")
    face(lamp)
    lines.append("o painting\nusemtl painting")  # 2 cm in front of the north wall, facing in
    face([(1.3, 1.1, D - 0.02), (1.3, 1.9, D - 0.02), (2.7, 1.9, D - 0.02), (2.7, 1.1, D - 0.02)])
    lines.append("o table\nusemtl oak")  # a block standing on the floor: no bottom face
    for q in box_outside(1.4, 0.0, 2.1, 2.6, 0.75, 2.9)[1:]:
        face(q)
    with open(os.path.join(room, "room.obj"), "w") as f:
        f.write("# radkit data/tools/make_own_models.py: 4 x 2.8 x 5 m room, metres, y up\n"
                "mtllib room.mtl\n")
        f.write("".join("v %g %g %g\n" % v for v in vertices))
        f.write("\n".join(lines) + "\n")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out", help="folder to write (created)")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    workshop(args.out)
    textured_room(args.out)
    print("wrote %s/bracket.stl, workshop.json, textured-room/room.obj (+ .mtl, textures/)" % args.out)


if __name__ == "__main__":
    main()
