#!/usr/bin/env python3
"""A stand-in for a scanned model (docs/bring-your-own-model.md): an icosphere of radius
100 mm, subdivided to 5 120 triangles, resting on the floor of the measured Cornell box, written
as scan.off beside scene.json (data/cornell-box.json plus the surface "scan"). As scans come,
it has the faults of one: 40 faces listed twice, a fin (a third face on one edge) and 10 faces
wound the other way. --clean leaves the faults out.

  python3 data/tools/make_scan.py --out /tmp/scan [--clean]
"""
import argparse, json, math, os

HERE = os.path.dirname(os.path.abspath(__file__))


def icosphere(levels):
    t = (1 + 5 ** 0.5) / 2
    v = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
         (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    v = [tuple(c / math.sqrt(sum(x * x for x in p)) for c in p) for p in v]
    f = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6),
         (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10),
         (8, 6, 7), (9, 8, 1)]
    for _ in range(levels):
        mid, out = {}, []

        def middle(a, b):
            key = (min(a, b), max(a, b))
            if key not in mid:
                p = [(x + y) / 2 for x, y in zip(v[a], v[b])]
                n = math.sqrt(sum(x * x for x in p))
                v.append(tuple(x / n for x in p))
                mid[key] = len(v) - 1
            return mid[key]

        for a, b, c in f:
            ab, bc, ca = middle(a, b), middle(b, c), middle(c, a)
            out += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        f = out
    return v, f


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", required=True)
    ap.add_argument("--clean", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    v, f = icosphere(4)
    centre, radius = (420, 100.5, 120), 100.0  # on the floor, clear of both blocks
    points = [tuple(c + radius * x for c, x in zip(centre, p)) for p in v]
    faces = list(f)
    if not a.clean:
        faces += [faces[k] for k in range(0, 4000, 100)]  # 40 faces listed twice
        for k in range(5, 5000, 500):  # 10 faces wound the other way
            faces[k] = faces[k][::-1]
        a0, b0, _ = faces[0]  # a fin: a third face on the edge a0-b0, standing off the sphere
        points.append(tuple(c + 1.3 * (x - c) for c, x in zip(centre, points[a0])))
        faces.append((b0, a0, len(points) - 1))
    with open(os.path.join(a.out, "scan.off"), "w") as out:
        out.write("OFF\n%d %d 0\n" % (len(points), len(faces)))
        out.writelines("%.6f %.6f %.6f\n" % p for p in points)
        out.writelines("3 %d %d %d\n" % t for t in faces)
    with open(os.path.join(HERE, "..", "cornell-box.json")) as src:
        scene = json.load(src)
    scene["name"] = "cornell-box-scan"
    scene["surfaces"].append({"name": "scan", "material": "white", "mesh": "scan.off"})
    with open(os.path.join(a.out, "scene.json"), "w") as out:
        json.dump(scene, out, indent=1)


if __name__ == "__main__":
    main()
