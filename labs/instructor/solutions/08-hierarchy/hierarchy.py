"""Lab 8: hierarchical radiosity, ε against links and error. Reference solution.

`labs/08-hierarchy/study.py --dir labs/instructor/solutions/08-hierarchy` runs the study on it.
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
    return RHO * EMISSION * r.area * point_factor(*r.centre, s)


# ---------------------------------------------------------------------------------------------
# Task 2: the oracle
# ---------------------------------------------------------------------------------------------
def link_error(r, s):
    """The link's error estimate in W: ρ B_s A_r (F_max − F_min), F over r's sample_points."""
    f = [point_factor(x, y, s) for x, y in sample_points(r)]
    return RHO * EMISSION * r.area * (max(f) - min(f))


# ---------------------------------------------------------------------------------------------
# Task 3: refinement
# ---------------------------------------------------------------------------------------------
def refine(eps, min_size=MIN_SIZE):
    """The links [(r, s), ...] of the hierarchy for threshold eps (W), starting from the whole
    floor and the whole lamp: a pair whose link_error is at most eps is linked; otherwise the
    larger element (the receiver on a tie) is split and each quarter paired with the other end.
    A pair whose larger element is no larger than min_size is linked as it is."""
    links, todo = [], [(FLOOR, LAMP)]
    while todo:
        r, s = todo.pop()
        split_receiver = r.size >= s.size
        if link_error(r, s) <= eps or max(r.size, s.size) <= min_size:
            links.append((r, s))
        elif split_receiver:
            todo.extend((c, s) for c in r.children())
        else:
            todo.extend((r, c) for c in s.children())
    return links


# ---------------------------------------------------------------------------------------------
# Task 4: from links to the floor's radiosity (push)
# ---------------------------------------------------------------------------------------------
def leaf_radiosity(links):
    """[(leaf, B), ...] over floor_leaves(links): B in W/m² at each leaf is the sum, over the
    links whose receiver contains the leaf, of the radiosity the link gives its receiver."""
    gathered = {}
    for r, s in links:
        gathered[r] = gathered.get(r, 0.0) + link_power(r, s) / r.area
    result = []
    for leaf in floor_leaves(links):
        b, node = 0.0, leaf
        while node is not None:            # the leaf and every ancestor that gathered light
            b += gathered.get(node, 0.0)
            node = node.parent()
        result.append((leaf, b))
    return result


# ---------------------------------------------------------------------------------------------
# Task 5: reading a radkit run
# ---------------------------------------------------------------------------------------------
def read_run(run_dir):
    """(links, mean, leaves) of a `radkit run --method hierarchical` folder on
    data/parallel-squares.json: the link count (report.json), the floor's mean red radiosity
    (surfaces.csv, surface "lower") and the floor's leaves [(Square, B), ...] (patches.csv)."""
    run = Path(run_dir)
    links = int(json.loads((run / "report.json").read_text())["hierarchy"]["links"])
    with open(run / "surfaces.csv") as f:
        mean = next(float(r["b_r_W_m2"]) for r in csv.DictReader(f) if r["surface"] == "lower")
    leaves = []
    with open(run / "patches.csv") as f:
        for row in csv.DictReader(f):
            if row["surface"] == "lower":
                size = math.sqrt(float(row["area_m2"]))
                square = Square("lower", float(row["cx_m"]) - size / 2,
                                float(row["cy_m"]) - size / 2, size)
                leaves.append((square, float(row["b_r_W_m2"])))
    return links, mean, leaves


# ---------------------------------------------------------------------------------------------
# Task 6: power laws
# ---------------------------------------------------------------------------------------------
def power_law(x, y):
    """(p, C) of the least-squares fit y ≈ C x^p: a straight line through (log x, log y)."""
    log_x, log_y = np.log(np.asarray(x, dtype=float)), np.log(np.asarray(y, dtype=float))
    p, log_c = np.polyfit(log_x, log_y, 1)
    return float(p), float(math.exp(log_c))
