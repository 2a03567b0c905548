#!/usr/bin/env python3
"""Runs every shipped scene through radkit's commands into one folder, or compares two such
folders file by file: the check that a restructuring changed no output.

  scripts/compare-runs.py run OUT [--radkit build/apps/radkit] [--quick]
  scripts/compare-runs.py diff BEFORE AFTER

`run` writes OUT/<case>/ for each case (a scene and the command's flags, listed below) and
OUT/cases.txt. `diff` compares every file byte for byte, except what measures the machine
rather than the result: in JSON reports the values whose keys speak of seconds, memory,
threads, dates or rates, in CSV files such columns (convergence.csv's time_s), and
convergence.png, which charts against seconds (its numbers are convergence.csv's). It prints
each difference and exits 1 when there is one.
"""
import argparse
import json
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# (case name, arguments after `radkit`); {out} is the case's folder. Sizes are small where the
# command's default would take minutes, so the whole set runs in a few minutes on 2 cores.
def cases(quick):
    scenes = sorted(p.stem for p in (ROOT / "data").glob("*.json"))
    patches = ["--patches", "600"] if quick else []
    out = []
    for s in scenes:
        scene = str(ROOT / "data" / f"{s}.json")
        out.append((f"run-{s}", ["run", scene, *patches, "--out", "{out}"]))
        out.append((f"hier-{s}", ["run", scene, "--method", "hierarchical", "--out", "{out}"]))
    cornell = str(ROOT / "data" / "cornell-box.json")
    glossy = str(ROOT / "data" / "cornell-box-glossy.json")
    small = ["--size", "64x64", "--spp", "4", "--patches", "400"]
    for shading in ["radiosity", "phong", "cook-torrance", "path-trace", "final-gather", "photon-map"]:
        out.append((f"render-{shading}", ["render", glossy, "--shading", shading, *small,
                                          "--photons", "20000", "--out", "{out}/render.pfm"]))
    out.append(("solvers-cornell", ["solvers", cornell, "--patches", "400",
                                    "--solvers", "jacobi,gauss-seidel,sor,southwell,cg",
                                    "--ff-enforce", "reciprocity", "--out", "{out}"]))
    out.append(("photons-cornell", ["photons", cornell, "--patches", "400", "--photons", "50000",
                                    "--out", "{out}"]))
    out.append(("brdf-table", ["brdf", "--table"]))  # prints its output: compared as stdout.txt
    out.append(("outdoor-sky", ["sky", "--size", "64", "--out", "{out}"]))
    out.append(("outdoor-clouds", ["clouds", "--width", "32", "--height", "18", "--samples", "4",
                                   "--out", "{out}"]))
    out.append(("outdoor-clouds-slab", ["clouds", "--scene", str(ROOT / "data/clouds/slab.json"),
                                        "--width", "32", "--height", "18", "--samples", "4",
                                        "--out", "{out}"]))
    out.append(("outdoor-terrain", ["terrain", "--resolution", "33", "--image", "--image-width",
                                    "64", "--image-height", "36", "--out", "{out}"]))
    out.append(("outdoor-pillars", ["pillars", "--size", "40", "24", "--samples", "2000",
                                    "--out", "{out}"]))
    return out


# Keys whose values measure the machine or the clock, not the result.
VOLATILE = re.compile(r"(second|time|memory|rss|bytes_per|peak|threads|date|host|rate|per_s|"
                      r"speed|elapsed|duration|cpu|wall|version|command|path|folder|file)",
                      re.IGNORECASE)


def strip(value):
    if isinstance(value, dict):
        return {k: strip(v) for k, v in value.items() if not VOLATILE.search(k)}
    if isinstance(value, list):
        return [strip(v) for v in value]
    return value


def strip_csv(data):
    rows = [line.split(",") for line in data.decode(errors="replace").splitlines()]
    if not rows:
        return rows
    keep = [i for i, name in enumerate(rows[0]) if not VOLATILE.search(name) and name != "time_s"]
    return [[r[i] for i in keep if i < len(r)] for r in rows]


def run(args):
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    names = []
    env = dict(os.environ, RADKIT_THREADS=os.environ.get("RADKIT_THREADS", "2"))
    for name, argv in cases(args.quick):
        if args.only and args.only not in name:
            continue
        folder = out / name
        folder.mkdir(exist_ok=True)
        cmd = [args.radkit] + [a.replace("{out}", str(folder)) for a in argv]
        r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           env=env)
        (folder / "exit.txt").write_text(f"{r.returncode}\n")
        if "{out}" not in " ".join(argv):
            (folder / "stdout.txt").write_text(r.stdout)
        # The log keeps the lines that do not carry a time, so a refused case compares too.
        log = [l for l in r.stdout.splitlines() if not re.search(r"\d+(\.\d+)? ?(s|ms|MiB|GiB)\b", l)]
        (folder / "log.txt").write_text("\n".join(log) + "\n")
        names.append(name)
        print(f"{name}: exit {r.returncode}", flush=True)
    if not args.only:  # a partial run adds to a folder and leaves its list alone
        (out / "cases.txt").write_text("\n".join(names) + "\n")


def diff(args):
    a, b = Path(args.before), Path(args.after)
    problems = []
    files_a = {p.relative_to(a) for p in a.rglob("*") if p.is_file()}
    files_b = {p.relative_to(b) for p in b.rglob("*") if p.is_file()}
    for p in sorted(files_a ^ files_b):
        problems.append(f"{p}: only in {'BEFORE' if p in files_a else 'AFTER'}")
    for p in sorted(files_a & files_b):
        x, y = (a / p).read_bytes(), (b / p).read_bytes()
        if x == y:
            continue
        if p.name == "log.txt":
            continue  # progress lines carry rates; exit.txt and the outputs decide
        if p.name == "convergence.png":
            continue
        if p.suffix == ".csv" and strip_csv(x) == strip_csv(y):
            continue
        if p.suffix == ".json":
            try:
                if strip(json.loads(x)) == strip(json.loads(y)):
                    continue
            except ValueError:
                pass
        problems.append(f"{p}: differs")
    for line in problems:
        print(line)
    print(f"{len(files_a & files_b)} files compared, {len(problems)} differences")
    return 1 if problems else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="what", required=True)
    r = sub.add_parser("run")
    r.add_argument("out")
    r.add_argument("--radkit", default=str(ROOT / "build" / "apps" / "radkit"))
    r.add_argument("--only", help="run only the cases whose name contains this text")
    r.add_argument("--quick", action="store_true", help="600 patches for the dense runs")
    d = sub.add_parser("diff")
    d.add_argument("before")
    d.add_argument("after")
    args = ap.parse_args()
    if args.what == "run":
        run(args)
        return 0
    return diff(args)


if __name__ == "__main__":
    sys.exit(main())
