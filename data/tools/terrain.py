"""The terrain heightfield shared by make_scenes.py (the terrain room) and
make_terrain_ladder.py (its larger versions): an n×n grid over size×size, two triangles a cell."""
import math
import struct
from array import array


def terrain_height(x, y):
    return 0.4 * math.sin(0.9 * x) * math.cos(0.7 * y) + 0.15 * math.sin(2.3 * x + 1.1 * y)


def write_terrain_ply(path, n, size=10.0, number="%.9g"):
    """The same terrain as write_terrain_off, as binary little-endian PLY (float coordinates,
    each the float nearest the `number`-formatted value the OFF holds: both files read the
    same). A fifth of the OFF's size, and read without parsing text."""
    vertices = array("f")
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = size * i / n, size * j / n
            vertices.extend((float(number % x), float(number % y), float(number % terrain_height(x, y))))
    if vertices.itemsize != 4:
        raise SystemExit("write_terrain_ply: this Python's array('f') is not 32-bit")
    row = struct.Struct("<Biii")
    with open(path, "wb") as out:
        out.write(b"ply\nformat binary_little_endian 1.0\ncomment radkit terrain (data/tools/terrain.py)\n"
                  b"element vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
                  b"element face %d\nproperty list uchar int vertex_indices\nend_header\n"
                  % ((n + 1) ** 2, 2 * n * n))
        if struct.pack("=I", 1) != struct.pack("<I", 1):
            vertices.byteswap()
        vertices.tofile(out)
        for j in range(n):
            faces = bytearray()
            for i in range(n):
                a, b, c, d = j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i
                faces += row.pack(3, a, b, c)
                faces += row.pack(3, a, c, d)
            out.write(faces)


def write_terrain_off(path, n, size=10.0, number="%.17g"):
    fmt = "%s %s %s\n" % (number, number, number)
    with open(path, "w") as out:
        out.write("OFF\n%d %d 0\n" % ((n + 1) ** 2, 2 * n * n))
        for j in range(n + 1):
            for i in range(n + 1):
                x, y = size * i / n, size * j / n
                out.write(fmt % (x, y, terrain_height(x, y)))
        for j in range(n):
            for i in range(n):
                a, b, c, d = j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i
                out.write("3 %d %d %d\n3 %d %d %d\n" % (a, b, c, a, c, d))
