#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets into OUT_DIR/<format>/ from data/: the JSON
scenes as they ship, and data/sphere-interior.off's icosphere as OFF, ASCII and binary PLY,
ASCII and binary STL and OBJ (with its MTL after a "#mtl" line, as fuzz_obj splits it);
run folders for fuzz_run_folder (run_folder_seeds); small systems as arrays for
fuzz_python_arrays (python_arrays_seeds).
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
    python_arrays_seeds(out)
    run_folder_seeds(out)


def python_arrays_seeds(out):
    """Seeds for fuzz_python_arrays in OUT_DIR/python_arrays/, in the byte layout of
    fuzz/python_arrays_fuzzer.cpp: small valid systems in each storage, and one refusal."""
    half, one, grey_half, unit_area = 0xF4, 0xFC, 100, 50  # F 0.5, F 1.0, rho 0.5, area 1
    lit = [100, 0, 0]  # emission (grey): patch 0 emits 1
    three = [0, half, half, half, 0, half, half, half, 0]
    grey = 4 | 8
    csr = [6] + [v for j, k in ((1, 2), (0, 2), (0, 1)) for v in (j, half, k, half)]
    seeds = {
        "dense3": [grey | 0, 3] + three + [unit_area] * 3 + [grey_half] * 3 + lit,
        "csr3": [grey | 1, 3] + csr + [2, 2, 2] + [unit_area] * 3 + [grey_half] * 3 + lit,
        "csc3": [grey | 2, 3] + csr + [2, 2, 2] + [unit_area] * 3 + [grey_half] * 3 + lit,
        # COO with F[0, 1] given twice (summed) and a patch that sees itself (F[1, 1]).
        "coo2": [grey | 3, 2, 4, 0, 1, half, 0, 1, half, 1, 0, half, 1, 1, half]
                + [unit_area] * 2 + [grey_half] * 2 + lit[:2],
        # Colour reflectance and emission, the per-patch norm, raw indptr.
        "csr3-rgb-raw": [1 | 0x10 | 0x20, 3] + csr + [4, 0, 2, 4, 6] + [unit_area] * 3
                        + [100, 150, 50] * 3 + [100, 80, 60] + [0] * 6,
        # Twelve patches seeing each other equally (rows sum to 1): a furnace.
        "dense12": [grey | 0, 12] + [0 if i == j else 218 for i in range(12) for j in range(12)]
                   + [unit_area] * 12 + [grey_half] * 12 + [100] + [0] * 11,
        # Column -5: refused.
        "csr3-minus5": [grey | 1, 3] + csr[:3] + [0xFB] + csr[4:] + [2, 2, 2] + [unit_area] * 3
                       + [grey_half] * 3 + lit,
        # Two plates seeing each other wholly, near-white.
        "plates": [grey | 0, 2, 0, one, one, 0, unit_area, unit_area, 0xEA, 0xEA, 100, 0],
    }
    os.makedirs(os.path.join(out, "python_arrays"), exist_ok=True)
    for name, data in seeds.items():
        with open(os.path.join(out, "python_arrays", name), "wb") as f:
            f.write(bytes(data))


# The files fuzz_run_folder reads, in the order of its seeds.
RUN_FILES = ["report.json", "radiosity.vtp", "formfactors.bin", "formfactors.mtx", "links.png",
             "convergence.csv", "surfaces.csv", "sky.pfm"]

# A three-patch folder in radkit's formats (the viewer tests' two walls), so the target has a
# seed without a radkit binary.
TWO_WALLS = {
    "report.json": b'{"scene": {"name": "two-walls", "units": "m", "surfaces": ["left wall", '
                   b'"right wall"], "camera": {"position": [0, 0, 3], "look_at": [0, 0, 0], '
                   b'"up": [0, 1, 0], "fov_deg": 40}}}\n',
    "radiosity.vtp": b"""<?xml version="1.0"?>
<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">
<PolyData>
<Piece NumberOfPoints="10" NumberOfPolys="3">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">
-1 -0.5 0 -0.05 -0.5 0 -0.05 0 0 -1 0 0 -0.05 0.5 0 -1 0.5 0 0.05 -0.5 0 1 -0.5 0 1 0.5 0 0.05 0.5 0
</DataArray></Points>
<Polys>
<DataArray type="Int64" Name="connectivity" format="ascii">
0 1 2 3 3 2 4 5 6 7 8 9
</DataArray>
<DataArray type="Int64" Name="offsets" format="ascii">
4 8 12
</DataArray>
</Polys>
<CellData Scalars="surface">
<DataArray type="Int32" Name="surface" format="ascii">
0 0 1
</DataArray>
<DataArray type="Float64" Name="area" format="ascii">
0.475 0.475 0.95
</DataArray>
<DataArray type="Float64" Name="reflectance" NumberOfComponents="3" format="ascii">
0.63 0.065 0.05 0.63 0.065 0.05 0.14 0.45 0.091
</DataArray>
<DataArray type="Float64" Name="emission" NumberOfComponents="3" format="ascii">
1 1 1 0 0 0 0 0 0
</DataArray>
<DataArray type="Float64" Name="radiosity" NumberOfComponents="3" format="ascii">
0.9 0.1 0.08 0.6 0.07 0.05 0.1 0.8 0.12
</DataArray>
</CellData>
</Piece>
</PolyData>
</VTKFile>
""",
    "formfactors.mtx": b"%%MatrixMarket matrix coordinate real general\n% test\n3 3 6\n"
                       b"1 2 0.25\n1 3 0.125\n2 1 0.25\n2 3 0.0625\n3 1 0.125\n3 2 0.0625\n",
    "convergence.csv": b"solver,iteration,time_s,residual,unshot_power_W\n"
                       b"jacobi,0,0.001,0.5,0.2\njacobi,1,0.002,0.05,0.1\n",
    "surfaces.csv": b"surface,area_m2,b_r_W_m2,b_g_W_m2,b_b_W_m2\n"
                    b'"left\nwall, ""west""",0.95,0.75,0.085,0.065\nright wall,0.95,0.1,0.8,0.12\n',
}


def sky_walls():
    """The two walls under a sky: report.json's "sky_panorama" frame and an 8 x 4 sky.pfm
    (little-endian floats, a blue sky over a grey ground)."""
    import json, struct
    files = dict(TWO_WALLS)
    report = json.loads(TWO_WALLS["report.json"])
    report["sky_panorama"] = {"file": "sky.pfm", "up": [0, 1, 0], "north": [0, 0, -1], "east": [1, 0, 0]}
    files["report.json"] = json.dumps(report).encode() + b"\n"
    rows = [(0.2, 0.4, 0.9)] * 16 + [(0.1, 0.1, 0.1)] * 16
    files["sky.pfm"] = b"PF\n8 4\n-1\n" + b"".join(struct.pack("<3f", *p) for p in rows)
    return files


def run_folder_input(files):
    """A run folder as one fuzz_run_folder input: each file after a line "%%file NAME"."""
    return b"".join(b"%%file " + name.encode() + b"\n" + files[name] + b"\n"
                    for name in RUN_FILES if name in files)


def run_folder_seeds(out):
    """Seeds for fuzz_run_folder in OUT_DIR/run_folder/: the two walls above, and when a radkit
    binary is found ($RADKIT_BINARY, else build-sanitize/'s or build/'s), folders it writes for
    the Cornell box: dense with formfactors.bin, dense with only formfactors.mtx, hierarchical
    with links.png. Each stays below run-fuzz.sh's -max_len of 64 KiB."""
    import json, shutil, subprocess, tempfile
    folder = os.path.join(out, "run_folder")
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "two-walls"), "wb") as f:
        f.write(run_folder_input(TWO_WALLS))
    with open(os.path.join(folder, "two-walls-sky"), "wb") as f:
        f.write(run_folder_input(sky_walls()))
    candidates = [os.environ.get("RADKIT_BINARY", "")] + [
        os.path.join(root, b, "apps", "radkit") for b in ("build-sanitize", "build")]
    radkit = next((c for c in candidates if c and os.access(c, os.X_OK)), None)
    if not radkit:
        print("make_seeds: no radkit binary; fuzz_run_folder gets only the two-walls seed")
        return
    scene = os.path.join(root, "data", "cornell-box.json")
    runs = {"dense": ["--patches", "24", "--write-matrix"],
            "hierarchical": ["--method", "hierarchical", "--epsilon", "0.1", "--min-area",
                             "20000", "--hr-rays", "4"]}
    work = tempfile.mkdtemp(prefix="radkit-seeds-")
    try:
        for name, options in runs.items():
            dest = os.path.join(work, name)
            done = subprocess.run([radkit, "run", scene, "--no-render", "--out", dest] + options,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
            if done.returncode != 0:
                print("make_seeds: `radkit run` for the %s seed failed: %s"
                      % (name, done.stderr.strip().splitlines()[-1:]))
                continue
            files = {}
            for f in RUN_FILES:
                if os.path.exists(os.path.join(dest, f)):
                    with open(os.path.join(dest, f), "rb") as src:
                        files[f] = src.read()
            # Only report.json's scene is read: the rest would draw most mutations into JSON
            # syntax errors before the other files are reached.
            files["report.json"] = json.dumps(
                {"scene": json.loads(files["report.json"])["scene"]}).encode() + b"\n"
            variants = {name: files}
            if "formfactors.mtx" in files:  # the .bin is read first when both are there
                variants[name + "-mtx"] = {k: v for k, v in files.items() if k != "formfactors.bin"}
                variants[name] = {k: v for k, v in files.items() if k != "formfactors.mtx"}
            for seed, chosen in variants.items():
                data = run_folder_input(chosen)
                if len(data) > 65536:
                    print("make_seeds: the %s seed is %d bytes, beyond -max_len" % (seed, len(data)))
                with open(os.path.join(folder, seed), "wb") as f:
                    f.write(data)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
