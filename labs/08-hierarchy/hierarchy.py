"""Lab 8: hierarchical radiosity, ε against links and error. Fill in the six tasks (README.md
says what each must return); labs/check 8 tells you what is still wrong.

squares.py, beside this file, is written for you: the elements (Square, FLOOR, LAMP), the
exact factor from a floor point to a lamp element, the sample points and the floor's leaves.
Then study.py, beside this file, makes the study of README.md (tables, hierarchy.png).
"""
import csv
import json
import math
from pathlib import Path

import numpy as np

# squares.py is in labs/08-hierarchy/; labs/check and study.py put that folder on the path.
from squares import (EMISSION, FLOOR, LAMP, MIN_SIZE, RHO, Square, floor_leaves,
                     point_factor, sample_points)


# ---------------------------------------------------------------------------------------------
# Task 1: what a link carries
# ---------------------------------------------------------------------------------------------
def link_power(r, s):
    """Power in W that the link r ← s brings to the floor element r from the lamp element s:
    ρ B_s A_r F̂_rs, with F̂_rs the factor from r's centre to s (point_factor)."""
    # TODO Task 1: RHO, EMISSION (the lamp's B), r.area, point_factor(*r.centre, s).
    raise NotImplementedError("Task 1: link_power (hierarchy.py)")


# ---------------------------------------------------------------------------------------------
# Task 2: the oracle
# ---------------------------------------------------------------------------------------------
def link_error(r, s):
    """The link's error estimate in W: ρ B_s A_r (F_max − F_min), F over r's sample_points."""
    # TODO Task 2: point_factor(x, y, s) at each of sample_points(r); README.md, "The oracle".
    raise NotImplementedError("Task 2: link_error (hierarchy.py)")


# ---------------------------------------------------------------------------------------------
# Task 3: refinement
# ---------------------------------------------------------------------------------------------
def refine(eps, min_size=MIN_SIZE):
    """The links [(r, s), ...] of the hierarchy for threshold eps (W), starting from the whole
    floor and the whole lamp: a pair whose link_error is at most eps is linked; otherwise the
    larger element (the receiver on a tie) is split and each quarter paired with the other end.
    A pair whose larger element is no larger than min_size is linked as it is."""
    # TODO Task 3: README.md, "Refinement". Start from (FLOOR, LAMP); Square.children() gives
    # the quarters. A list of pairs still to look at (or a recursive function) will do.
    raise NotImplementedError("Task 3: refine (hierarchy.py)")


# ---------------------------------------------------------------------------------------------
# Task 4: from links to the floor's radiosity (push)
# ---------------------------------------------------------------------------------------------
def leaf_radiosity(links):
    """[(leaf, B), ...] over floor_leaves(links): B in W/m² at each leaf is the sum, over the
    links whose receiver contains the leaf, of the radiosity the link gives its receiver."""
    # TODO Task 4: README.md, "Push". Square.parent() walks from a leaf up to FLOOR.
    raise NotImplementedError("Task 4: leaf_radiosity (hierarchy.py)")


# ---------------------------------------------------------------------------------------------
# Task 5: reading a radkit run
# ---------------------------------------------------------------------------------------------
def read_run(run_dir):
    """(links, mean, leaves) of a `radkit run --method hierarchical` folder on
    data/parallel-squares.json: the link count (report.json), the floor's mean red radiosity
    (surfaces.csv, surface "lower") and the floor's leaves [(Square, B), ...] (patches.csv)."""
    # TODO Task 5: json for report.json's "hierarchy", csv.DictReader for the CSV files;
    # columns in docs/formats.md. A floor patch is a square: its side is sqrt(area_m2).
    raise NotImplementedError("Task 5: read_run (hierarchy.py)")


# ---------------------------------------------------------------------------------------------
# Task 6: power laws
# ---------------------------------------------------------------------------------------------
def power_law(x, y):
    """(p, C) of the least-squares fit y ≈ C x^p: a straight line through (log x, log y)."""
    # TODO Task 6: numpy.polyfit on the logs; the intercept is log C.
    raise NotImplementedError("Task 6: power_law (hierarchy.py)")
