"""Lab 8's study, written for you: once the tasks of hierarchy.py pass `labs/check 8`, run

    python3 labs/08-hierarchy/study.py [--dir DIR] [--radkit PATH] [--out DIR] [--no-cornell]

to print the tables of README.md and draw hierarchy.png; hand in its output.
"""
import argparse
import csv
import json
import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True  # importing the student's file leaves no __pycache__ there
LAB = Path(__file__).resolve().parent
sys.path.insert(0, str(LAB.parent))
sys.path.insert(0, str(LAB))  # squares.py, which hierarchy.py imports
from pyradkit import (data_file, find_radkit, load_student, need_radkit, run_radkit,  # noqa: E402
                      run_study, save_figure)
from squares import (C11, EMISSION, LAMP, RHO, floor_leaves, l1_error, leaf_mean,  # noqa: E402
                     quadtree_leaves)

EXACT_POWER = RHO * EMISSION * C11
SQUARES_EPS = [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6]
CORNELL_EPS = [1e-3, 3e-4, 1e-4, 3e-5, 1e-5]


def hierarchical(radkit, scene, eps, out):
    """radkit run --method hierarchical at eps; (wall seconds, report.json)."""
    start = time.perf_counter()
    run_radkit(radkit, "run", scene, "--method", "hierarchical", "--epsilon", eps, "--seed", 1,
               "--threads", 2, "--no-render", "--out", out)
    seconds = time.perf_counter() - start
    return seconds, json.loads((Path(out) / "report.json").read_text())


def surface_means(run):
    with open(Path(run) / "surfaces.csv") as f:
        return {r["surface"]: np.array([float(r[c]) for c in ("b_r_W_m2", "b_g_W_m2", "b_b_W_m2")])
                for r in csv.DictReader(f)}


def main():
    parser = argparse.ArgumentParser(description="Lab 8: ε against links and error")
    parser.add_argument("--radkit", help="the radkit command (default: build/apps/radkit)")
    parser.add_argument("--out", default=".", help="folder for hierarchy.png (default: here)")
    parser.add_argument("--no-cornell", action="store_true",
                        help="leave out the Cornell box (about 10 s of the study's 13)")
    parser.add_argument("--dir", default=str(LAB),
                        help="folder with your hierarchy.py (default: this lab's folder)")
    args = parser.parse_args()
    radkit = need_radkit(find_radkit(args.radkit), 8)
    lab = load_student(args.dir, "hierarchy.py")
    eps = np.array(SQUARES_EPS)

    # A: your refinement of the parallel squares.
    print(f"A. your refine on the parallel squares (data/parallel-squares.json): the floor's "
          f"power -> rho E C-11 = {EXACT_POWER:.10f} W")
    print(f"{'eps':>7s} {'links':>7s} {'floor':>6s} {'lamp':>5s} {'dense':>7s} "
          f"{'power error':>12s} {'sum of errs':>11s} {'L1 error':>9s} {'means L1':>9s} "
          f"{'seconds':>8s}")
    mine = {"links": [], "l1": [], "power": [], "bound": []}
    for e in SQUARES_EPS:
        start = time.perf_counter()
        links = lab.refine(e)
        leaves = lab.leaf_radiosity(links)
        seconds = time.perf_counter() - start
        power = math.fsum(lab.link_power(r, s) for r, s in links)
        bound = math.fsum(lab.link_error(r, s) for r, s in links)
        floor = floor_leaves(links)
        lamp = quadtree_leaves([s for _, s in links], LAMP)
        l1 = l1_error(leaves)
        means = l1_error([(leaf, leaf_mean(leaf)) for leaf in floor])  # the leaves' share alone
        for key, value in (("links", len(links)), ("l1", l1), ("power", abs(power - EXACT_POWER)),
                           ("bound", bound)):
            mine[key].append(value)
        print(f"{e:7.0e} {len(links):7d} {len(floor):6d} {len(lamp):5d} "
              f"{len(floor) * len(lamp):7d} {power - EXACT_POWER:+12.3e} {bound:11.3e} "
              f"{l1:9.3e} {means:9.3e} {seconds:8.3f}")
    fits = {key: lab.power_law(eps, mine[key]) for key in ("links", "l1", "power")}
    print("fits against eps: links {:.1f} eps^{:.3f}; L1 error {:.3g} eps^{:.3f}; power error "
          "{:.3g} eps^{:.3f}".format(*fits["links"][::-1], *fits["l1"][::-1],
                                     *fits["power"][::-1]))
    p, c = lab.power_law(mine["links"], mine["l1"])
    print(f"L1 error against links: {c:.3g} links^{p:.3f}")

    # B: radkit's hierarchical method on the same scene.
    theirs = {"links": [], "l1": []}
    with tempfile.TemporaryDirectory() as tmp:
        print("\nB. radkit run --method hierarchical on the same scene")
        print(f"{'eps':>7s} {'links':>7s} {'floor':>6s} {'mean - rho E C-11':>18s} "
              f"{'L1 error':>9s} {'seconds':>8s}")
        for e in SQUARES_EPS:
            out = Path(tmp) / f"squares-{e:g}"
            seconds, _ = hierarchical(radkit, data_file("parallel-squares.json"), e, out)
            links, mean, leaves = lab.read_run(out)
            l1 = l1_error(leaves)
            theirs["links"].append(links)
            theirs["l1"].append(l1)
            print(f"{e:7.0e} {links:7d} {len(leaves):6d} {mean - EXACT_POWER:+18.2e} {l1:9.3e} "
                  f"{seconds:8.3f}")
        rk = {key: lab.power_law(eps, theirs[key]) for key in ("links", "l1")}
        print("fits against eps: links {:.1f} eps^{:.3f}; L1 error {:.3g} eps^{:.3f}".format(
            *rk["links"][::-1], *rk["l1"][::-1]))

        cornell = None
        if not args.no_cornell:
            cornell = {"eps": [], "leaves": [], "links": []}
            runs = {}
            for e in CORNELL_EPS:
                out = Path(tmp) / f"cornell-{e:g}"
                seconds, report = hierarchical(radkit, data_file("cornell-box.json"), e, out)
                runs[e] = (seconds, report["hierarchy"], surface_means(out))
            finest = runs[CORNELL_EPS[-1]][2]
            print(f"\nC. radkit run --method hierarchical on data/cornell-box.json; the change "
                  f"is the largest relative difference of a surface mean (any channel) from "
                  f"eps = {CORNELL_EPS[-1]:g}")
            print(f"{'eps':>7s} {'leaves':>7s} {'links':>8s} {'N^2':>10s} {'links/N^2':>10s} "
                  f"{'change':>9s} {'seconds':>8s}")
            for e in CORNELL_EPS:
                seconds, h, means = runs[e]
                n = h["leaves"]
                change = max(float(np.max(np.abs(means[s] / finest[s] - 1))) for s in finest)
                cornell["eps"].append(e)
                cornell["leaves"].append(n)
                cornell["links"].append(h["links"])
                print(f"{e:7.0e} {n:7d} {h['links']:8d} {n * n:10d} {h['links'] / n ** 2:10.2e} "
                      f"{change:9.2e} {seconds:8.2f}")
            p, c = lab.power_law(cornell["eps"], cornell["links"])
            q, d = lab.power_law(cornell["leaves"], cornell["links"])
            print(f"fits: links {c:.1f} eps^{p:.3f}; links {d:.3g} leaves^{q:.3f}")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4.2))
    left.loglog(eps, mine["links"], "o-", label="links, yours (squares)")
    left.loglog(eps, theirs["links"], "s--", label="links, radkit (squares)")
    if cornell:
        left.loglog(cornell["eps"], cornell["links"], "^-", label="links, radkit (Cornell box)")
        left.loglog(cornell["eps"], np.array(cornell["leaves"], dtype=float) ** 2, "k:",
                    label="N² pairs on the same leaves (Cornell)")
    left.set_xlabel("ε (W)")
    left.set_ylabel("links")
    left.set_title("links against ε")
    right.loglog(eps, mine["l1"], "o-", label="floor's L1 error, yours")
    right.loglog(eps, theirs["l1"], "s--", label="floor's L1 error, radkit")
    right.loglog(eps, mine["power"], "v-", label="floor's power error, yours")
    right.loglog(eps, mine["bound"], "k:", label="Σ link errors (bounds both of yours)")
    right.set_xlabel("ε (W)")
    right.set_ylabel("W")
    right.set_title("error against ε, parallel squares")
    for ax in (left, right):
        ax.invert_xaxis()   # finer to the right
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    save_figure(fig, args.out, "hierarchy.png", dpi=110)


if __name__ == "__main__":
    run_study(main, 8)
