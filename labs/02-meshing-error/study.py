"""Lab 2's study, written for you: once the tasks of meshing.py pass `labs/check 2`, run

    python3 labs/02-meshing-error/study.py [--dir DIR] [--radkit PATH] [--out DIR] [--cornell]

to print the tables of README.md and draw meshing-error.png; hand in its output.
"""
import argparse
import csv
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True  # importing the student's file leaves no __pycache__ there
LAB = Path(__file__).resolve().parent
sys.path.insert(0, str(LAB.parent))
from pyradkit import (data_file, find_radkit, load_student, need_radkit, run_radkit,  # noqa: E402
                      run_study, save_figure)


def run(radkit, scene, patches, out):
    """radkit run at a patch count, solved far below the meshing error (tolerance 1e-10)."""
    run_radkit(radkit, "run", scene, "--patches", patches, "--tol", "1e-10", "--seed", 1,
               "--threads", 2, "--no-render", "--out", out)
    return out


def series(lab, radkit, scene, surface, counts, tmp):
    """(means, peaks) of a surface over runs at the patch counts."""
    results = [lab.surface_radiosity(run(radkit, scene, n, Path(tmp) / f"{Path(scene).stem}-{n}"),
                                 surface) for n in counts]
    return np.array([r[0] for r in results]), np.array([r[1] for r in results])


def main():
    parser = argparse.ArgumentParser(description="Lab 2: the meshing-error study")
    parser.add_argument("--radkit", help="the radkit command (default: build/apps/radkit)")
    parser.add_argument("--out", default=".", help="folder for meshing-error.png (default: here)")
    parser.add_argument("--cornell", action="store_true",
                        help="also the Cornell box at 250 to 4000 patches (about a minute)")
    parser.add_argument("--dir", default=str(LAB),
                        help="folder with your meshing.py (default: this lab's folder)")
    args = parser.parse_args()
    radkit = need_radkit(find_radkit(args.radkit), 2)
    lab = load_student(args.dir, "meshing.py")
    point_limit, loglog_slope, extrapolate = lab.point_limit, lab.loglog_slope, lab.extrapolate
    observed_order = lab.observed_order
    counts = np.array([8, 32, 128, 512, 2048])   # two unit squares of k x k patches, k = 2 .. 32

    with tempfile.TemporaryDirectory() as tmp:
        # A: the floor's peak under the lamp, whose limit is a closed form.
        exact = point_limit(0.5, 1.0, 1.0, 1.0, 1.0)
        means, peaks = series(lab, radkit, data_file("parallel-squares.json"), "lower", counts, tmp)
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
            m, _ = series(lab, radkit, LAB / scene, surface, counts, tmp)
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
                out = run(radkit, data_file("cornell-box.json"), n, Path(tmp) / f"cornell-{n}")
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
    save_figure(fig, args.out, "meshing-error.png", dpi=120)


if __name__ == "__main__":
    run_study(main, 2)
