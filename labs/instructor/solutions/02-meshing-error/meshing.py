"""Lab 2: meshing error. Reference solution.

`labs/02-meshing-error/study.py --dir labs/instructor/solutions/02-meshing-error` runs the study on it.
"""
import csv
import math
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
