#!/usr/bin/env python3
"""Top-down map of a run's patches (a hierarchical run's leaves) from its radiosity.vtp: every
patch facing up (normal +z) inside a rectangle of the xy plane, filled by its radiosity
(luminance, log scale) and outlined, so the refinement can be seen next to the light it follows.
Each patch fills its bounding box: meant for axis-aligned rectangles (a street, a floor).

    python3 data/tools/leaf_map.py RUN/radiosity.vtp OUT.png --x -5 5 --y -20 20 --size 1200

--transpose draws y across and x down (for a long, narrow street). Standard library only.
"""
import argparse
import math
import re
import struct
import zlib


def arrays(path):
    text = open(path).read()
    out = {}
    for m in re.finditer(r'<DataArray([^>]*)>(.*?)</DataArray>', text, re.S):
        head, body = m.group(1), m.group(2)
        name = re.search(r'Name="([^"]*)"', head)
        key = name.group(1) if name else 'points'
        out[key] = [float(v) for v in body.split()]
    return out


def write_png(path, width, height, rows):
    raw = b''.join(b'\x00' + bytes(r) for r in rows)

    def chunk(kind, data):
        c = struct.pack('>I', len(data)) + kind + data
        return c + struct.pack('>I', zlib.crc32(kind + data) & 0xffffffff)

    with open(path, 'wb') as f:
        f.write(b'\x89PNG\r\n\x1a\n')
        f.write(chunk(b'IHDR', struct.pack('>IIBBBBB', width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b'IDAT', zlib.compress(raw, 9)))
        f.write(chunk(b'IEND', b''))


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('vtp')
    p.add_argument('png')
    p.add_argument('--x', type=float, nargs=2, required=True)
    p.add_argument('--y', type=float, nargs=2, required=True)
    p.add_argument('--size', type=int, default=1024, help='pixels along the longer side')
    p.add_argument('--transpose', action='store_true')
    a = p.parse_args()
    d = arrays(a.vtp)
    pts, conn, offs, rad = d['points'], d['connectivity'], d['offsets'], d['radiosity']
    (x0, x1), (y0, y1) = a.x, a.y
    u0, u1, v0, v1 = (y0, y1, x0, x1) if a.transpose else (x0, x1, y0, y1)
    scale = a.size / max(u1 - u0, v1 - v0)
    w, h = int(round((u1 - u0) * scale)), int(round((v1 - v0) * scale))
    img = [[40, 40, 60] * w for _ in range(h)]
    polys, start = [], 0
    for i, end in enumerate(offs):
        ids = [int(k) for k in conn[start:int(end)]]
        start = int(end)
        q = [(pts[3 * k], pts[3 * k + 1], pts[3 * k + 2]) for k in ids]
        nz = (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0])
        if nz <= 0 or any(abs(v[2] - q[0][2]) > 1e-9 for v in q):
            continue
        r, g, b = rad[3 * i:3 * i + 3]
        polys.append((q, 0.2126 * r + 0.7152 * g + 0.0722 * b))
    lums = [l for _, l in polys if l > 0]
    lo, hi = (min(lums), max(lums)) if lums else (1, 2)
    to_px = (lambda x, y: ((y - u0) * scale, (x - v0) * scale)) if a.transpose else \
        (lambda x, y: ((x - u0) * scale, (v1 - y) * scale))
    for q, l in polys:
        t = 0 if l <= 0 else (math.log(l) - math.log(lo)) / max(1e-9, math.log(hi) - math.log(lo))
        # dark blue through orange to pale yellow
        col = [int(255 * min(1, max(0, c))) for c in (0.1 + 1.1 * t, 0.05 + 0.95 * t * t, 0.3 + 0.5 * t ** 4)]
        px = [to_px(v[0], v[1]) for v in q]
        ca, cb = min(p[0] for p in px), max(p[0] for p in px)
        ra, rb = min(p[1] for p in px), max(p[1] for p in px)
        for row in range(max(0, int(ra)), min(h, int(math.ceil(rb)))):
            for c in range(max(0, int(ca)), min(w, int(math.ceil(cb)))):
                edge = (c - ca < 1 or cb - c <= 1 or row - ra < 1 or rb - row <= 1)
                img[row][3 * c:3 * c + 3] = [20, 20, 20] if edge else col
    write_png(a.png, w, h, img)


if __name__ == '__main__':
    main()
