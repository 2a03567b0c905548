"""Lab 1's study, written for you: once the tasks of formfactor.py pass `labs/check 1`, run

    python3 labs/01-form-factors/study.py [--dir DIR] [--radkit PATH] [--out DIR]

to print the comparisons with Howell and radkit and draw near-field.png; hand in its output.
"""
import argparse
import json
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True  # importing the student's file leaves no __pycache__ there
LAB = Path(__file__).resolve().parent
sys.path.insert(0, str(LAB.parent))
from pyradkit import (data_file, find_radkit, load_student, need_radkit,  # noqa: E402
                      radkit_surface_factors, run_study, save_figure)


def scene_polygons(path):
    """{surface name: polygon} of a scene file whose surfaces are single polygons."""
    return {s["name"]: np.array(s["polygon"], dtype=float)
            for s in json.loads(Path(path).read_text())["surfaces"]}


def main():
    parser = argparse.ArgumentParser(description="Lab 1: the comparisons and near-field.png")
    parser.add_argument("--radkit", help="the radkit command (default: build/apps/radkit)")
    parser.add_argument("--out", default=".", help="folder for near-field.png (default: here)")
    parser.add_argument("--dir", default=str(LAB),
                        help="folder with your formfactor.py (default: this lab's folder)")
    args = parser.parse_args()
    radkit = need_radkit(find_radkit(args.radkit), 1)
    lab = load_student(args.dir, "formfactor.py")
    form_factor, near_field_errors = lab.form_factor, lab.near_field_errors
    unit_squares, howell_c11, howell_c14 = lab.unit_squares, lab.howell_c11, lab.howell_c14

    print("Gauss-Legendre n x n on patch i against Howell (relative error):")
    cases = [("C-11 unit squares 1 apart", unit_squares(1.0), howell_c11(1, 1, 1)),
             ("C-11 1 x 1.5 at 0.5", ([[0, 0, 0], [1, 0, 0], [1, 1.5, 0], [0, 1.5, 0]],
                                      [[0, 0, .5], [0, 1.5, .5], [1, 1.5, .5], [1, 0, .5]]),
              howell_c11(1, 1.5, 0.5)),
             ("C-14 W = 1, H = 2", ([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
                                    [[0, 0, 0], [0, 0, 2], [1, 0, 2], [1, 0, 0]]),
              howell_c14(1, 1, 2)),
             # The other way round, F21 = F12 A1/A2 by reciprocity: over the wall, whose
             # integrand has a kink at the common edge (README.md, question 2).
             ("C-14 F21 over the wall", ([[0, 0, 0], [0, 0, 2], [1, 0, 2], [1, 0, 0]],
                                         [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]),
              howell_c14(1, 1, 2) / 2)]
    print(f"{'case':28s} {'exact':>12s}" + "".join(f"{'n=' + str(n):>10s}"
                                                    for n in (1, 2, 4, 8, 16)))
    for name, (pi, pj), exact in cases:
        errs = [abs(form_factor(pi, pj, n) - exact) / exact for n in (1, 2, 4, 8, 16)]
        print(f"{name:28s} {exact:12.9f}" + "".join(f"{e:10.2e}" for e in errs))

    print("\nAgainst radkit formfactors (F_ij both ways, n = 8):")
    for scene in (data_file("parallel-squares.json"),
                  data_file("perpendicular-squares.json"), LAB / "tilted-pair.json"):
        polygons, ref = scene_polygons(scene), radkit_surface_factors(radkit, scene)
        (a, pa), (b, pb) = polygons.items()
        for i, pi, j, pj in ((a, pa, b, pb), (b, pb, a, pa)):
            mine = form_factor(pi, pj, 8)
            print(f"  {scene.name:26s} F({i} -> {j}) = {mine:.10f}  radkit {ref[(i, j)]:.10f}"
                  f"  difference {mine - ref[(i, j)]:+.1e}")

    distances = np.array([2, 1, 0.5, 0.25, 0.1, 0.05, 0.02])
    rules = (1, 2, 3, 4, 8)
    print("\nUnit squares approaching: relative error of the n x n rule against C-11")
    print(f"{'d':>6s}" + "".join(f"{'n=' + str(n):>10s}" for n in rules))
    table = np.array([near_field_errors(distances, n) for n in rules])
    for k, d in enumerate(distances):
        print(f"{d:6.2f}" + "".join(f"{table[r, k]:10.2e}" for r in range(len(rules))))
    for tol in (1e-3, 1e-6):
        needed = []
        for d in distances:
            n = 1
            while near_field_errors([d], n)[0] > tol and n < 64:
                n += 1
            needed.append(n)
        print(f"points per side for a relative error below {tol:g}: " +
              ", ".join(f"d = {d:g}: {n}" for d, n in zip(distances, needed)))

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4))
    for r, n in enumerate(rules):
        ax.loglog(distances, np.maximum(table[r], 1e-16), "o-", label=f"{n} x {n} points")
    ax.set_xlabel("distance d between unit squares")
    ax.set_ylabel("relative error against Howell C-11")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    save_figure(fig, args.out, "near-field.png", dpi=120)


if __name__ == "__main__":
    run_study(main, 1)
