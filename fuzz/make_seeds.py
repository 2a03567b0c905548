#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets into OUT_DIR/<format>/ from data/: the JSON
scenes as they ship, and data/sphere-interior.off's icosphere as OFF, ASCII and binary PLY,
ASCII and binary STL and OBJ (with its MTL after a "#mtl" line, as fuzz_obj splits it).
Usage: fuzz/make_seeds.py OUT_DIR"""
import os, sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(root, "data", "tools"))
from mutate_inputs import seeds  # the mutation run's seeds: one definition of the shapes

MTL = b"newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\n"


def main():
    out = sys.argv[1]
    for name, data, kind in seeds(os.path.join(root, "data")):
        ext = os.path.splitext(name)[1][1:]
        if ext == "obj":
            data += b"#mtl\n" + MTL
        os.makedirs(os.path.join(out, ext), exist_ok=True)
        with open(os.path.join(out, ext, name), "wb") as f:
            f.write(data)
    for name in sorted(os.listdir(os.path.join(root, "data"))):  # shipped meshes, small ones
        path = os.path.join(root, "data", name)
        if name.endswith(".off") and os.path.getsize(path) < 200000:
            with open(path, "rb") as src, open(os.path.join(out, "off", name), "wb") as f:
                f.write(src.read())


if __name__ == "__main__":
    main()
