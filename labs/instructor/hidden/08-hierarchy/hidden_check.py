"""Hidden cases for lab 8 (labs/grade.py runs them besides check_lab.py): other element pairs
and other x. Oracles: link powers and errors evaluated once with mpmath at 40 digits (Howell B-3
summed over the lamp element's corners, at r's centre and at r's nine sample points) and written
down here; a power law y = C x^p, whose fit is (p, C) by construction, and a series that is no
power law, whose least-squares fit was evaluated once with mpmath at 40 digits.

Catches what the public cases (where F over r is extreme at a corner or at the centre) miss: a
link_error that spreads F over r's corners and centre only, forgetting the edge middles; it is
26 % low for the whole floor under a lamp element at its edge."""
import math
import sys

import numpy as np

from pyradkit import LABS, guarded, load_student

sys.path.insert(0, str(LABS / "08-hierarchy"))  # squares.py, which hierarchy.py imports
from squares import FLOOR, Square  # noqa: E402

TASK_OF = {"link_power": 1, "link_error": 2, "power_law": 6}
# (r, s, P̂_rs, e_rs, e_rs over the corners and centre only) in W. The first two pairs have F
# extreme at an edge middle of r; the last two have r smaller than s, and s off to one side.
PAIRS = [(FLOOR, Square("upper", 0.25, 0.0, 0.25),
          0.0073609490942864984, 0.0070326941193920622, 0.0052089388621133903),
         (Square("lower", 0.5, 0.0, 0.5), Square("upper", 0.0, 0.0, 0.5),
          0.0061902294657269316, 0.0044827951046325094, 0.0036929830836058481),
         (Square("lower", 0.75, 0.125, 0.125), Square("upper", 0.0, 0.5, 0.5),
          0.00023486471942663464, 7.7265275129481526e-5, None),
         (Square("lower", 0.25, 0.5, 0.25), Square("upper", 0.375, 0.125, 0.125),
          0.0001085402572403774, 4.2637573612367026e-5, None)]
# x unevenly spaced and above 1 (link counts, as the study fits the L1 error against them).
X = np.array([16.0, 52.0, 64.0, 256.0, 964.0, 1024.0, 3904.0])
SERIES = [(lambda x: 0.0182 * x ** -0.273, "y = 0.0182 x^-0.273", (-0.273, 0.0182)),
          (lambda x: 0.5 * x ** 0.6 * (1 + 0.25 * np.cos(np.arange(len(x)))),
           "y = 0.5 x^0.6 with ±25 % ripples, not a power", (0.59048974097090138,
                                                             0.5314509412442007))]


def name(e):
    where = "floor" if e.surface == "lower" else "lamp"
    return f"{where} [{e.x0:g}, {e.x0 + e.size:g}] x [{e.y0:g}, {e.y0 + e.size:g}]"


def check(student_dir, radkit=None):
    lab = load_student(student_dir, "hierarchy.py")
    failures = []
    task = guarded(failures, TASK_OF)

    for r, s, power, _, _ in PAIRS:
        got = task("link_power", lambda: float(lab.link_power(r, s)))
        if got is None:
            break
        if not math.isclose(got, power, rel_tol=1e-12):
            failures.append(f"Task 1 (hidden case): link_power({name(r)}, {name(s)}) = "
                            f"{got:.10g} W, expected {power:.10g} W (ρ B_s A_r F at r's centre).")
            break
    for r, s, _, error, five in PAIRS:
        got = task("link_error", lambda: float(lab.link_error(r, s)))
        if got is None:
            break
        if not math.isclose(got, error, rel_tol=1e-12, abs_tol=1e-15):
            hint = (" That is the spread over r's corners and centre only: F can be largest or "
                    "smallest at the middle of an edge, so take all nine sample_points(r)."
                    if five is not None and math.isclose(got, five, rel_tol=1e-9) else
                    " ρ B_s A_r (F_max − F_min) over r's nine sample points.")
            failures.append(f"Task 2 (hidden case): link_error({name(r)}, {name(s)}) = "
                            f"{got:.10g} W, expected {error:.10g} W.{hint}")
            break

    for f, what, (p, c) in SERIES:
        got = task("power_law", lambda: tuple(map(float, lab.power_law(X.copy(), f(X)))))
        if got is None:
            break
        if not (len(got) == 2 and math.isclose(got[0], p, rel_tol=1e-9)
                and math.isclose(got[1], c, rel_tol=1e-9)):
            failures.append(f"Task 6 (hidden case): power_law on {what} at x = "
                            f"{X.astype(int).tolist()} gave {got}, expected ({p:.10g}, "
                            f"{c:.10g}): least squares through (log x, log y) for any x, "
                            "not only ε.")
            break
    return failures
