"""Lab 1: form factors by hand. Reference solution.

Polygons are (k, 3) arrays of vertices, counter-clockwise seen from their front side (the side
their normal points to). Run this file to print the comparisons and draw near-field.png:

    python3 formfactor.py [--radkit PATH] [--out DIR]
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np


# ---------------------------------------------------------------------------------------------
# Task 1: the point-to-polygon form factor (Lambert's contour formula)
# ---------------------------------------------------------------------------------------------
def point_to_polygon(x, normal, polygon):
    """Form factor from a differential area at x with unit normal `normal` to the polygon,
    which must lie wholly in front of x (no clipping here)."""
    x = np.asarray(x, dtype=float)
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n)
    v = np.asarray(polygon, dtype=float) - x
    v /= np.linalg.norm(v, axis=1)[:, None]          # unit vectors towards the vertices
    w = np.roll(v, -1, axis=0)                       # v_{k+1}
    c = np.cross(v, w)
    s = np.linalg.norm(c, axis=1)                    # sin(gamma_k)
    gamma = np.arctan2(s, np.einsum("ij,ij->i", v, w))  # angle, accurate for small gamma too
    # An edge whose line passes through x contributes nothing (gamma = 0 or its plane is n's).
    term = np.divide(gamma * (c @ n), s, out=np.zeros_like(s), where=s > 0)
    # The sum is negative when the polygon faces x (its vertices then run clockwise seen from
    # x); the magnitude is the projected solid angle over pi.
    return abs(term.sum()) / (2.0 * math.pi)


# ---------------------------------------------------------------------------------------------
# Task 2: an n x n Gauss-Legendre rule on a parallelogram
# ---------------------------------------------------------------------------------------------
def gauss_legendre_rule(polygon, n):
    """Points (n*n, 3) and weights (n*n,) of the tensor Gauss-Legendre rule on the
    parallelogram P0 P1 P2 P3; the weights sum to its area."""
    P = np.asarray(polygon, dtype=float)
    if len(P) != 4 or not np.allclose(P[0] + P[2], P[1] + P[3]):
        raise ValueError("gauss_legendre_rule: the polygon must be a parallelogram P0 P1 P2 P3")
    e1, e2 = P[1] - P[0], P[3] - P[0]
    t, w = np.polynomial.legendre.leggauss(n)
    u, wu = (t + 1.0) / 2.0, w / 2.0                 # [-1, 1] -> [0, 1]: the weights halve
    a, b = np.meshgrid(u, u, indexing="ij")
    points = P[0] + a.reshape(-1, 1) * e1 + b.reshape(-1, 1) * e2
    weights = np.outer(wu, wu).ravel() * np.linalg.norm(np.cross(e1, e2))
    return points, weights


def polygon_normal(polygon):
    """Unit normal by the right-hand rule (Newell's method: exact for planar polygons)."""
    P = np.asarray(polygon, dtype=float)
    n = np.cross(P, np.roll(P, -1, axis=0)).sum(axis=0)
    return n / np.linalg.norm(n)


# ---------------------------------------------------------------------------------------------
# Task 3: the patch-to-patch form factor by quadrature over patch i
# ---------------------------------------------------------------------------------------------
def form_factor(polygon_i, polygon_j, n=8):
    """F_ij, the fraction of the light leaving patch i that arrives at patch j:
    (1/A_i) * integral over A_i of point_to_polygon(x, n_i, polygon_j) dA, with the n x n
    Gauss-Legendre rule on patch i (a parallelogram)."""
    points, weights = gauss_legendre_rule(polygon_i, n)
    normal = polygon_normal(polygon_i)
    values = np.array([point_to_polygon(x, normal, polygon_j) for x in points])
    return float(weights @ values / weights.sum())


# ---------------------------------------------------------------------------------------------
# Task 4: the catalogue's closed forms (Howell C-11 and C-14)
# ---------------------------------------------------------------------------------------------
def howell_c11(a, b, c):
    """F_12 between identical, parallel, directly opposed a x b rectangles at distance c."""
    X, Y = a / c, b / c
    x1, y1 = math.sqrt(1 + X * X), math.sqrt(1 + Y * Y)
    return 2.0 / (math.pi * X * Y) * (
        math.log(x1 * y1 / math.sqrt(1 + X * X + Y * Y))
        + X * y1 * math.atan(X / y1) + Y * x1 * math.atan(Y / x1)
        - X * math.atan(X) - Y * math.atan(Y))


def howell_c14(l, w, h):
    """F_12 from the l x w rectangle to the l x h rectangle, perpendicular with the common
    edge of length l."""
    W, H = w / l, h / l
    W2, H2 = W * W, H * H
    R2 = W2 + H2
    R = math.sqrt(R2)
    log_term = (math.log((1 + W2) * (1 + H2) / (1 + R2))
                + W2 * math.log(W2 * (1 + R2) / ((1 + W2) * R2))
                + H2 * math.log(H2 * (1 + R2) / ((1 + H2) * R2)))
    return (W * math.atan(1 / W) + H * math.atan(1 / H) - R * math.atan(1 / R)
            + 0.25 * log_term) / (math.pi * W)


# ---------------------------------------------------------------------------------------------
# Task 5: a few-point rule as two patches approach
# ---------------------------------------------------------------------------------------------
def unit_squares(d):
    """Directly opposed unit squares at distance d, facing each other: (lower, upper)."""
    lower = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
    upper = [[0, 0, d], [0, 1, d], [1, 1, d], [1, 0, d]]
    return lower, upper


def near_field_errors(distances, n):
    """Relative error |F_n - F| / F of the n x n rule for unit squares at each distance, F from
    Howell C-11."""
    errors = []
    for d in distances:
        exact = howell_c11(1.0, 1.0, d)
        errors.append(abs(form_factor(*unit_squares(d), n=n) - exact) / exact)
    return np.array(errors)


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


def scene_polygons(path):
    """{surface name: polygon} of a scene file whose surfaces are single polygons."""
    return {s["name"]: np.array(s["polygon"], dtype=float)
            for s in json.loads(Path(path).read_text())["surfaces"]}


def radkit_factors(radkit, scene):
    """{(from, to): F} from `radkit formfactors` (one patch per surface, default method)."""
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([radkit, "formfactors", str(scene), "--patches", "2", "--seed", "1",
                        "--threads", "2", "--out", f"{tmp}/ff"], check=True, capture_output=True)
        with open(f"{tmp}/ff/surface_formfactors.csv") as f:
            return {(r["from"], r["to"]): float(r["F"]) for r in csv.DictReader(f)}


def main():
    parser = argparse.ArgumentParser(description="Lab 1: the comparisons and near-field.png")
    parser.add_argument("--radkit", help="the radkit command (default: build/apps/radkit)")
    parser.add_argument("--out", default=".", help="folder for near-field.png (default: here)")
    args = parser.parse_args()
    repo = repo_root()
    radkit = find_radkit(args.radkit, repo)

    print("Gauss-Legendre n x n on patch i against Howell (relative error):")
    cases = [("C-11 unit squares 1 apart", unit_squares(1.0), howell_c11(1, 1, 1)),
             ("C-11 1 x 1.5 at 0.5", ([[0, 0, 0], [1, 0, 0], [1, 1.5, 0], [0, 1.5, 0]],
                                      [[0, 0, .5], [0, 1.5, .5], [1, 1.5, .5], [1, 0, .5]]),
              howell_c11(1, 1.5, 0.5)),
             ("C-14 W = 1, H = 2", ([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]],
                                    [[0, 0, 0], [0, 0, 2], [1, 0, 2], [1, 0, 0]]),
              howell_c14(1, 1, 2))]
    print(f"{'case':28s} {'exact':>12s}" + "".join(f"{'n=' + str(n):>10s}"
                                                    for n in (1, 2, 4, 8, 16)))
    for name, (pi, pj), exact in cases:
        errs = [abs(form_factor(pi, pj, n) - exact) / exact for n in (1, 2, 4, 8, 16)]
        print(f"{name:28s} {exact:12.9f}" + "".join(f"{e:10.2e}" for e in errs))

    print("\nAgainst radkit formfactors (F_ij both ways, n = 8):")
    for scene in (repo / "data" / "parallel-squares.json",
                  repo / "data" / "perpendicular-squares.json",
                  repo / "labs" / "01-form-factors" / "tilted-pair.json"):
        polygons, ref = scene_polygons(scene), radkit_factors(radkit, scene)
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
    fig.tight_layout()
    out = Path(args.out) / "near-field.png"
    fig.savefig(out, dpi=120)
    print(f"\nwrote {out}")


if __name__ == "__main__":
    try:
        main()
    except NotImplementedError as e:
        sys.exit(f"{e} is not done yet; labs/check 1 says what is missing")
