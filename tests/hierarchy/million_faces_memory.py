#!/usr/bin/env python3
"""Bytes per input face of a hierarchical run at a million input triangles: builds the scaling
ladder's terrain (data/tools/make_terrain_ladder.py), runs `radkit run --method hierarchical
--no-render` and checks report.json's memory against the bound below. About a minute and
1.3 GiB on two cores: labelled `long`, which the sanitizer job leaves out; run it alone with
`ctest --test-dir build -L long`.

    million_faces_memory.py RADKIT MAKE_TERRAIN_LADDER"""
import json
import os
import subprocess
import sys
import tempfile

# Peak resident bytes per input face the run may reach (docs/hierarchical.md measures 1.33 kB
# at this size; 3.4 kB before the hierarchy's arrays were made compact). The bound leaves 15 %
# for the allocator and the libraries, not room for a regression of the arrays.
BOUND = 1530

radkit, ladder = sys.argv[1], sys.argv[2]
with tempfile.TemporaryDirectory() as tmp:
    subprocess.run([sys.executable, ladder, tmp, "--triangles", "1000000"], check=True,
                   stdout=subprocess.DEVNULL)
    scene = [f for f in os.listdir(tmp) if f.endswith(".json")][0]
    out = os.path.join(tmp, "run")
    subprocess.run([radkit, "run", os.path.join(tmp, scene), "--method", "hierarchical",
                    "--no-render", "--out", out], check=True, stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL)
    with open(os.path.join(out, "report.json")) as f:
        report = json.load(f)
memory = report["memory"]
faces = memory["input_faces"]
per_face = memory["peak_bytes_per_input_face"]
stages = {s["stage"]: s for s in memory["stages"]}
print("input faces %d, peak %.0f MiB, %.0f bytes per input face (bound %d)" %
      (faces, max(s["peak_bytes"] for s in memory["stages"]) / 2**20, per_face, BOUND))
for s in memory["stages"]:
    print("  %-16s resident %6.0f MiB  peak %6.0f MiB" %
          (s["stage"], s["resident_bytes"] / 2**20, s["peak_bytes"] / 2**20))
if faces < 900000:
    sys.exit("expected about a million input faces, got %d" % faces)
if not per_face <= BOUND:
    sys.exit("%.0f bytes per input face exceed the bound %d: see which stage grew above" %
             (per_face, BOUND))
