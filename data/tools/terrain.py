"""The terrain heightfield shared by make_scenes.py (the terrain room) and
make_terrain_ladder.py (its larger versions): an n×n grid over size×size, two triangles a cell."""
import math


def write_terrain_off(path, n, size=10.0, number="%.17g"):
    fmt = "%s %s %s\n" % (number, number, number)
    with open(path, "w") as out:
        out.write("OFF\n%d %d 0\n" % ((n + 1) ** 2, 2 * n * n))
        for j in range(n + 1):
            for i in range(n + 1):
                x, y = size * i / n, size * j / n
                z = 0.4 * math.sin(0.9 * x) * math.cos(0.7 * y) + 0.15 * math.sin(2.3 * x + 1.1 * y)
                out.write(fmt % (x, y, z))
        for j in range(n):
            for i in range(n):
                a, b, c, d = j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i
                out.write("3 %d %d %d\n3 %d %d %d\n" % (a, b, c, a, c, d))
