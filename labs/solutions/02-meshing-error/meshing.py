"""Lab 2: meshing error. Reference solution.

Run this file to make the study of README.md (tables, meshing-error.png):

    python3 meshing.py [--radkit PATH] [--out DIR] [--cornell]
"""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np


# ---------------------------------------------------------------------------------------------
# Task 1: read a surface's radiosity from a radkit run folder
# ---------------------------------------------------------------------------------------------
def surface_radiosity(run_dir, surface):
    """(mean, peak) red-channel radiosity of the named surface in W/m²: the area-weighted mean
    over its patches (surfaces.csv) and the largest patch value (patches.csv)."""
    with open(Path(run_dir) / "surfaces.csv") as f:
        mean = next(float(r["b_r_W_m2"]) for r in csv.DictReader(f) if r["surface"] == surface)
    with open(Path(run_dir) / "patches.csv") as f:
        peak = max(float(r["b_r_W_m2"]) for r in csv.DictReader(f) if r["surface"] == surface)
    return mean, peak


# ---------------------------------------------------------------------------------------------
# Task 2: the converged peak, a closed form (Howell B-3 by superposition)
# ---------------------------------------------------------------------------------------------
def point_limit(rho, emission, a, b, h):
    """Radiosity at the point of a black-lit floor (reflectance rho) right under the centre of
    a parallel a x b emitter (exitance `emission`, W/m²) at height h: rho * emission * F, F the
    point-to-rectangle factor: four B-3 rectangles of a/2 x b/2, each with a corner above it."""
    X, Y = a / 2 / h, b / 2 / h
    x1, y1 = math.sqrt(1 + X * X), math.sqrt(1 + Y * Y)
    corner = (X / x1 * math.atan(Y / x1) + Y / y1 * math.atan(X / y1)) / (2 * math.pi)
    return rho * emission * 4 * corner


# ---------------------------------------------------------------------------------------------
# Task 3: the slope of a power law
# ---------------------------------------------------------------------------------------------
def loglog_slope(x, y):
    """Least-squares slope of log y against log x: the p of y ~ C x^p."""
    logx, logy = np.log(np.asarray(x, dtype=float)), np.log(np.asarray(y, dtype=float))
    return float(np.polyfit(logx, logy, 1)[0])


# ---------------------------------------------------------------------------------------------
# Task 4: Richardson extrapolation
# ---------------------------------------------------------------------------------------------
def richardson(coarse, fine, ratio, order):
    """The converged value estimated from two runs whose error falls like s^order, s shrinking
    by `ratio` (> 1) from the coarse run to the fine one."""
    return fine + (fine - coarse) / (ratio ** order - 1.0)


# ---------------------------------------------------------------------------------------------
# Task 5: the order of convergence from three runs
# ---------------------------------------------------------------------------------------------
def observed_order(coarse, medium, fine, ratio):
    """The p of error ~ s^p from three runs with s shrinking by `ratio` at each step."""
    return math.log((coarse - medium) / (medium - fine)) / math.log(ratio)


# ---------------------------------------------------------------------------------------------
# Task 6: from patch counts to the converged value
# ---------------------------------------------------------------------------------------------
def extrapolate(patch_counts, values, order):
    """Richardson estimate from the last two runs of a series at the given total patch counts,
    for a quantity whose error falls like h^order, h the patch size (h ~ 1/sqrt(N) on a surface
    split into N patches)."""
    ratio_h = math.sqrt(patch_counts[-1] / patch_counts[-2])   # h shrinks by the root of N's ratio
    return richardson(values[-2], values[-1], ratio_h, order)


# ---------------------------------------------------------------------------------------------
# The study (written for you): run it once the tasks are done and hand in its output.
# ---------------------------------------------------------------------------------------------
def repo_root():
    """The radkit repository this file (or the current folder) is in."""
    for start in (Path(__file__).resolve(), Path.cwd().resolve()):
        for folder in start.parents if start.is_file() else (start, *start.parents):
            if (folder / "data" / "parallel-squares.json").is_file():
                return folder
    sys.exit("the radkit repository (its data/ folder) was not found above this file or the "
             "current folder. Fix: run from inside the repository")


def find_radkit(option, repo):
    for candidate in (option, os.environ.get("RADKIT"), repo / "build" / "apps" / "radkit"):
        if candidate and Path(candidate).is_file():
            return str(candidate)
    found = shutil.which("radkit")
    if not found:
        sys.exit("radkit not found. Fix: build it with `bash scripts/build.sh` from the repository "
                 "root, or pass --radkit PATH (or set RADKIT)")
    return found


def run(radkit, scene, patches, out):
    """radkit run at a patch count, solved far below the meshing error (tolerance 1e-10)."""
    subprocess.run([radkit, "run", str(scene), "--patches", str(patches), "--tol", "1e-10",
                    "--seed", "1", "--threads", "2", "--no-render", "--out", str(out)],
                   check=True, capture_output=True)
    return out


def series(radkit, scene, surface, counts, tmp):
    """(means, peaks) of a surface over runs at the patch counts."""
    results = [surface_radiosity(run(radkit, scene, n, Path(tmp) / f"{Path(scene).stem}-{n}"),
                                 surface) for n in counts]
    return np.array([r[0] for r in results]), np.array([r[1] for r in results])


def main():
    parser = argparse.ArgumentParser(description="Lab 2: the meshing-error study")
    parser.add_argument("--radkit", help="the radkit command (default: build/apps/radkit)")
    parser.add_argument("--out", default=".", help="folder for meshing-error.png (default: here)")
    parser.add_argument("--cornell", action="store_true",
                        help="also the Cornell box at 250 to 4000 patches (about a minute)")
    args = parser.parse_args()
    repo = repo_root()
    radkit = find_radkit(args.radkit, repo)
    lab = repo / "labs" / "02-meshing-error"
    counts = np.array([8, 32, 128, 512, 2048])   # two unit squares of k x k patches, k = 2 .. 32

    with tempfile.TemporaryDirectory() as tmp:
        # A: the floor's peak under the lamp, whose limit is a closed form.
        exact = point_limit(0.5, 1.0, 1.0, 1.0, 1.0)
        means, peaks = series(radkit, repo / "data" / "parallel-squares.json", "lower", counts, tmp)
        print(f"A. data/parallel-squares.json, surface 'lower': peak radiosity -> {exact:.10f} "
              "(Howell B-3, rho E F at the centre)")
        print(f"{'patches':>8s} {'h':>8s} {'mean':>14s} {'peak':>14s} {'error':>10s} "
              f"{'Richardson':>14s} {'its error':>10s} {'order':>6s}")
        for k, n in enumerate(counts):
            rich = extrapolate(counts[:k + 1], peaks[:k + 1], 2) if k else float("nan")
            order = observed_order(*peaks[k - 2:k + 1], 2.0) if k >= 2 else float("nan")
            print(f"{n:8d} {1 / math.sqrt(n / 2):8.4f} {means[k]:14.10f} {peaks[k]:14.10f} "
                  f"{exact - peaks[k]:10.2e} {rich:14.10f} {rich - exact:10.1e} {order:6.3f}")
        errors = exact - peaks
        slope = loglog_slope(counts, errors)
        print(f"slope of log(error) against log(patches): {slope:.3f}; against log(h): "
              f"{loglog_slope(1 / np.sqrt(counts / 2), errors):.3f}")

        # B: surface means with interreflection: no closed form; successive differences.
        plots = [("peak, parallel squares (B-3 limit)", counts, errors)]
        for scene, surface in (("reflective-squares.json", "lower"),
                               ("reflective-corner.json", "floor")):
            m, _ = series(radkit, lab / scene, surface, counts, tmp)
            diffs = np.abs(np.diff(m))
            order = observed_order(*m[-3:], 2.0)
            print(f"\nB. {scene}, surface '{surface}': mean radiosity")
            print(f"{'patches':>8s} {'mean':>14s} {'change':>10s} {'order':>6s}")
            for k, n in enumerate(counts):
                o = observed_order(*m[k - 2:k + 1], 2.0) if k >= 2 else float("nan")
                change = m[k] - m[k - 1] if k else float("nan")
                print(f"{n:8d} {m[k]:14.10f} {change:10.2e} {o:6.3f}")
            print("slope of log(change) against log(patches): "
                  f"{loglog_slope(counts[1:], diffs):.3f}; "
                  f"extrapolated with order 2: {extrapolate(counts, m, 2):.8f}, with the observed "
                  f"order {order:.2f}: {extrapolate(counts, m, order):.8f}")
            plots.append((f"mean change, {scene.removesuffix('.json')}", counts[1:], diffs))

        if args.cornell:
            cornell = [250, 500, 1000, 2000, 4000]
            surfaces = None
            table = []
            for n in cornell:
                out = run(radkit, repo / "data" / "cornell-box.json", n, Path(tmp) / f"cornell-{n}")
                with open(out / "surfaces.csv") as f:
                    rows = list(csv.DictReader(f))
                surfaces = [r["surface"] for r in rows]
                table.append([[float(r[c]) for c in ("b_r_W_m2", "b_g_W_m2", "b_b_W_m2")]
                              for r in rows])
            table = np.array(table)
            change = np.abs(np.diff(table, axis=0) / table[1:]).max(axis=(1, 2))
            worst = [surfaces[np.abs(np.diff(table, axis=0) / table[1:])[k].max(axis=1).argmax()]
                     for k in range(len(cornell) - 1)]
            print("\nC. data/cornell-box.json: largest relative change of a surface mean "
                  "(any channel)")
            for k in range(1, len(cornell)):
                print(f"{cornell[k - 1]:6d} -> {cornell[k]:6d}: {change[k - 1]:.2e} "
                      f"({worst[k - 1]})")
            print("slope of log(change) against log(patches): "
                  f"{loglog_slope(cornell[1:], change):.3f}")
            plots.append(("largest mean change, Cornell box", np.array(cornell[1:]), change))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for label, x, y in plots:
        ax.loglog(x, y, "o-", label=label)
    ax.loglog(counts, errors[0] * counts[0] / counts, "k:", label="slope -1 (error ~ h²)")
    ax.set_xlabel("patches (both surfaces)")
    ax.set_ylabel("W/m² (Cornell: relative)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = Path(args.out) / "meshing-error.png"
    fig.savefig(path, dpi=120)
    print(f"\nwrote {path}")


if __name__ == "__main__":
    try:
        main()
    except NotImplementedError as e:
        sys.exit(f"{e} is not done yet; labs/check 2 says what is missing")
