#!/usr/bin/env python3
"""Write the inward unit cube, each face an n x n grid, in View3D's .vs3 input format.

The patches and windings are those of `radkit formfactors data/cube-one-emitter.json
--patches 6n²`, so the two programs can be timed on the same geometry (docs/benchmarks.md).
Usage: scripts/cube_vs3.py N > cube.vs3
"""
import sys


def main():
    if len(sys.argv) != 2 or not sys.argv[1].isdigit() or int(sys.argv[1]) < 1:
        sys.exit("cube_vs3.py: expected one positive integer N (patches per face edge), got "
                 f"{sys.argv[1:]}. Fix: scripts/cube_vs3.py 30 > cube30.vs3")
    n = int(sys.argv[1])
    # origin, u, v per face, with u x v pointing into the cube
    faces = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((0, 0, 1), (0, 1, 0), (1, 0, 0)),
             ((0, 0, 0), (0, 1, 0), (0, 0, 1)), ((1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 0, 0), (0, 0, 1), (1, 0, 0)), ((0, 1, 0), (1, 0, 0), (0, 0, 1))]
    vertices, surfaces = [], []
    for o, u, v in faces:
        for i in range(n):
            for j in range(n):
                base = len(vertices)
                for a, b in ((i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)):
                    vertices.append(tuple(o[k] + u[k] * a / n + v[k] * b / n for k in range(3)))
                surfaces.append((base + 1, base + 2, base + 3, base + 4))
    out = ["T inward unit cube, %d x %d patches per face" % (n, n),
           "C encl=1 list=0 eps=1e-4 out=0", "F 3"]
    out += ["V %d %.17g %.17g %.17g" % (k + 1, *p) for k, p in enumerate(vertices)]
    out += ["S %d %d %d %d %d 0 0 0.5 s%d" % (k + 1, *s, k + 1) for k, s in enumerate(surfaces)]
    out.append("End of data")
    print("\n".join(out))


if __name__ == "__main__":
    main()
