"""Lab 2: meshing error. Fill in the six tasks (README.md says what each must return);
labs/check 2 tells you what is still wrong.

Then study.py, beside this file, makes the study of README.md (tables, meshing-error.png).
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
    # TODO Task 1: read surfaces.csv and patches.csv (csv.DictReader); columns in docs/formats.md.
    raise NotImplementedError("Task 1: surface_radiosity (meshing.py)")


# ---------------------------------------------------------------------------------------------
# Task 2: the converged peak, a closed form (Howell B-3 by superposition)
# ---------------------------------------------------------------------------------------------
def point_limit(rho, emission, a, b, h):
    """Radiosity at the point of a black-lit floor (reflectance rho) right under the centre of
    a parallel a x b emitter (exitance `emission`, W/m²) at height h: rho * emission * F, F the
    point-to-rectangle factor: four B-3 rectangles of a/2 x b/2, each with a corner above it."""
    # TODO Task 2: Howell B-3 (README.md) for a/2 x b/2 at height h, four times, times rho E.
    raise NotImplementedError("Task 2: point_limit (meshing.py)")


# ---------------------------------------------------------------------------------------------
# Task 3: the slope of a power law
# ---------------------------------------------------------------------------------------------
def loglog_slope(x, y):
    """Least-squares slope of log y against log x: the p of y ~ C x^p."""
    # TODO Task 3: a least-squares straight line through (log x, log y); numpy.polyfit helps.
    raise NotImplementedError("Task 3: loglog_slope (meshing.py)")


# ---------------------------------------------------------------------------------------------
# Task 4: Richardson extrapolation
# ---------------------------------------------------------------------------------------------
def richardson(coarse, fine, ratio, order):
    """The converged value estimated from two runs whose error falls like s^order, s shrinking
    by `ratio` (> 1) from the coarse run to the fine one."""
    # TODO Task 4: README.md, "Richardson extrapolation".
    raise NotImplementedError("Task 4: richardson (meshing.py)")


# ---------------------------------------------------------------------------------------------
# Task 5: the order of convergence from three runs
# ---------------------------------------------------------------------------------------------
def observed_order(coarse, medium, fine, ratio):
    """The p of error ~ s^p from three runs with s shrinking by `ratio` at each step."""
    # TODO Task 5: README.md, "The order from three runs".
    raise NotImplementedError("Task 5: observed_order (meshing.py)")


# ---------------------------------------------------------------------------------------------
# Task 6: from patch counts to the converged value
# ---------------------------------------------------------------------------------------------
def extrapolate(patch_counts, values, order):
    """Richardson estimate from the last two runs of a series at the given total patch counts,
    for a quantity whose error falls like h^order, h the patch size (h ~ 1/sqrt(N) on a surface
    split into N patches)."""
    # TODO Task 6: Richardson on the last two values; what is the ratio of their patch sizes?
    raise NotImplementedError("Task 6: extrapolate (meshing.py)")
