"""Check for lab 2: meshing error (meshing.py).

Oracles: Howell's B-3 (a point under one corner of a parallel rectangle; docs/oracles.md) gives
the converged peak radiosity of data/parallel-squares.json's floor, rho E 4 B-3(a/2, b/2, h).
Synthetic series whose limit and order are known exactly test the slope, Richardson and order
formulas. radkit runs (in a temporary folder) supply the real series.

Tolerances: on synthetic data rounding only (1e-9). On radkit's series, Richardson's estimate
keeps the next term of the error, O(h⁴). The reference solution measures it at 3.1e-6 from the
runs at 128 and 512 patches (and at 2.0e-7 from 512 and 2048: a factor of 16 per halving of h,
as O(h⁴) predicts). The tolerance is 1e-5. The usual mistakes (the wrong exponent, no
extrapolation, the sign) leave 2.8e-4 or more.
"""
import csv
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from pyradkit import (data_file, guarded, howell_b3 as b3, load_student,  # noqa: E402
                      need_radkit, run_radkit, sentence, slope_mistakes, which)

RICHARDSON_TOLERANCE = 1e-5
RICHARDSON_MEASURED = 3.1e-6  # the reference solution's remainder from 128 and 512 patches
COUNTS = [8, 32, 128, 512]    # two unit squares of k x k patches, k = 2, 4, 8, 16
TASK_OF = {"surface_radiosity": 1, "point_limit": 2, "loglog_slope": 3, "richardson": 4,
           "observed_order": 5, "extrapolate": 6}


def read_run(run_dir, surface):
    """(mean, peak) red-channel radiosity of a surface, read here independently of the student."""
    with open(Path(run_dir) / "surfaces.csv") as f:
        mean = next(float(r["b_r_W_m2"]) for r in csv.DictReader(f) if r["surface"] == surface)
    with open(Path(run_dir) / "patches.csv") as f:
        peak = max(float(r["b_r_W_m2"]) for r in csv.DictReader(f) if r["surface"] == surface)
    return mean, peak


def extrapolation_mistakes(counts, values, p):
    """(sentence, value) for the usual slips in Task 6 on a series."""
    c, v = values[-2], values[-1]
    r = counts[-1] / counts[-2]
    return [
        ("the wrong exponent: you used the patch-count ratio N2/N1 with the order in h. The error "
         "is C h^order and h ~ N^(-1/2), so per run it shrinks by (N2/N1)^(order/2): use ratio "
         "sqrt(N2/N1) with the order, or N2/N1 with order/2", v + (v - c) / (r ** p - 1)),
        ("the exponent is halved twice: sqrt(N2/N1) goes with the order in h itself, not order/2",
         v + (v - c) / (math.sqrt(r) ** (p / 2) - 1)),
        ("that uses the first two runs; the last two are the most accurate (on an exact power law "
         "both give the limit, on real runs only the finest pair comes close)",
         values[1] + (values[1] - values[0]) / (math.sqrt(counts[1] / counts[0]) ** p - 1)),
        ("the ratio is upside down: h shrinks, so the ratio is sqrt(N_fine/N_coarse) > 1",
         v + (v - c) / (math.sqrt(1 / r) ** p - 1)),
        ("no extrapolation: that is the last value", v),
    ]


# --- the tasks -----------------------------------------------------------------------------------
def check_reading(lab, task, failures, run_dir, expected):
    for surface, (mean, peak) in expected.items():
        got = task("surface_radiosity",
                   lambda: tuple(map(float, lab.surface_radiosity(str(run_dir), surface))))
        if got is None:
            return False
        if len(got) != 2:
            failures.append(f"Task 1, surface_radiosity returned {len(got)} values; return the "
                            "pair (mean, peak).")
            return False
        if not (math.isclose(got[0], mean, rel_tol=1e-12)
                and math.isclose(got[1], peak, rel_tol=1e-12)):
            lamp = 1.0 if surface == "lower" else None
            hint = which(got[1], [("the peak is the lamp's (1 W/m²): keep only the rows whose "
                                   "surface column names the surface", lamp),
                                  ("mean and peak are swapped: return (mean, peak)", mean)])
            hint = hint or ("the mean is surfaces.csv's b_r_W_m2 (area-weighted), the peak the "
                            "largest b_r_W_m2 of the surface's rows in patches.csv")
            failures.append(f"Task 1, surface_radiosity(run at 32 patches, '{surface}') = {got}; "
                            f"the files say mean {mean:.10g}, peak {peak:.10g}. {sentence(hint)}")
            return False
    return True


def check_point_limit(lab, task, failures):
    for args in ((0.5, 1.0, 1.0, 1.0, 1.0), (0.8, 2.0, 2.0, 1.0, 0.5)):
        rho, e, a, b, h = args
        got = task("point_limit", lambda: float(lab.point_limit(*args)))
        if got is None:
            return False
        F = 4 * b3(a / 2, b / 2, h)
        exact = rho * e * F
        if not math.isclose(got, exact, rel_tol=1e-9):
            hint = which(got, [
                ("that is B-3 for the whole rectangle with its corner above the point: the point "
                 "is under the centre, so split the rectangle into four a/2 x b/2 ones, each with "
                 "a corner above the point, and add them (superposition)", rho * e * b3(a, b, h)),
                ("that is one of the four quarter rectangles: add all four (multiply by 4)",
                 rho * e * F / 4),
                ("four corners of the full size: each quarter is a/2 x b/2",
                 rho * e * 4 * b3(a, b, h)),
                ("the reflectance is missing: the floor reflects rho of what arrives, "
                 "B = rho E F", e * F),
                ("the emission is missing: B = rho E F", rho * F),
                ("that is the form factor F alone: B = rho E F", F),
            ]) or "B = rho E F, F = 4 B-3(a/2, b/2, h), B-3 as in README.md"
            failures.append(f"Task 2, point_limit(rho={rho}, emission={e}, a={a}, b={b}, h={h}) "
                            f"= {got:.10g}; Howell B-3 gives {exact:.10g}. {sentence(hint)}")
            return False
    return True


def check_slope(lab, task, failures):
    x = np.array([8.0, 32, 128, 512, 2048])
    for y, what in ((0.3 * x ** -1.25, "y = 0.3 x^-1.25"),
                    (0.02 / x * (1 + 3 / np.sqrt(x)), "y = 0.02/x (1 + 3/sqrt(x)), not a power")):
        got = task("loglog_slope", lambda: float(lab.loglog_slope(x.copy(), y.copy())))
        if got is None:
            return False
        exact = float(np.polyfit(np.log(x), np.log(y), 1)[0])
        if not math.isclose(got, exact, rel_tol=1e-9):
            hint = which(got, slope_mistakes(
                x, y, "the error falls as the patch count grows, so the slope is negative")) \
                or "fit a straight line to (log x, log y) by least squares and return its slope"
            failures.append(f"Task 3, loglog_slope on {what} at x = 8 .. 2048: {got:.6g}, "
                            f"expected {exact:.6g}. {sentence(hint)}")
            return False
    return True


def check_richardson(lab, task, failures):
    cases = [((0.3125, 0.303125, 2.0, 2.0), "f = 0.3 + 0.05 h², h = 0.5 then 0.25"),
             ((0.1, 0.3 - 0.2 * 3 ** -1.5, 3.0, 1.5), "f = 0.3 - 0.2 h^1.5, h = 1 then 1/3")]
    for (coarse, fine, r, p), what in cases:
        got = task("richardson", lambda: float(lab.richardson(coarse, fine, r, p)))
        if got is None:
            return False
        if not math.isclose(got, 0.3, rel_tol=1e-9):
            step = fine - coarse
            hint = which(got, [
                ("no extrapolation: that is the fine value", fine),
                ("the sign of the correction is reversed: the limit lies beyond the fine value, "
                 "fine + (fine - coarse)/(ratio^order - 1)", fine - step / (r ** p - 1)),
                ("divide by ratio^order - 1, not ratio^order: the coarse error is ratio^order "
                 "times the fine one, so their difference is (ratio^order - 1) times it",
                 fine + step / r ** p),
                ("the order is ignored (ratio - 1): the error falls like s^order, so the factor "
                 "is ratio^order - 1", fine + step / (r - 1)),
                ("the exponent is doubled: ratio^(2 order) - 1; is your ratio already squared?",
                 fine + step / (r ** (2 * p) - 1)),
                ("ratio and order are swapped: ratio^order, not order^ratio",
                 fine + step / (p ** r - 1)),
                ("that is the mean of the two runs, not an extrapolation", (coarse + fine) / 2),
            ]) or "fine + (fine - coarse) / (ratio^order - 1)"
            failures.append(f"Task 4, richardson on {what} (ratio {r:g}, order {p:g}): "
                            f"{got:.10g}, the limit is 0.3. {sentence(hint)}")
            return False
    return True


def check_order(lab, task, failures):
    for sign in (1, -1):
        f = [2 + sign * 0.3 * h ** 1.5 for h in (1.0, 0.5, 0.25)]
        got = task("observed_order", lambda: float(lab.observed_order(*f, 2.0)))
        if got is None:
            return False
        if not math.isclose(got, 1.5, rel_tol=1e-9):
            bases = "log10 in one place and ln in the other"
            hint = which(got, [
                ("the differences are the wrong way up: (coarse - medium)/(medium - fine), the "
                 "larger change over the smaller", -1.5),
                ("not divided by log(ratio)", 1.5 * math.log(2)),
                (bases, 1.5 * math.log10(2) / math.log(2)),
                (bases, 1.5 * math.log(2) / math.log10(2)),
                ("the values are used where their differences belong",
                 math.log(f[0] / f[1]) / math.log(2)),
            ]) or "p = log((coarse - medium)/(medium - fine)) / log(ratio)"
            failures.append(f"Task 5, observed_order on f = 2 {'+' if sign > 0 else '-'} "
                            f"0.3 h^1.5 at h = 1, 1/2, 1/4: {got:.6g}, expected 1.5. "
                            f"{sentence(hint)}")
            return False
    return True


def check_extrapolate(lab, task, failures, peaks, richardson_ok):
    synthetic = [([8, 32, 128], 2.0, lambda n: 0.3 + 1.4 / n, "f = 0.3 + 0.7 h², h² = 2/N"),
                 ([50, 200, 450], 1.5, lambda n: 0.3 + 0.4 * n ** -0.75,
                  "f = 0.3 + 0.4 h^1.5, h = 1/sqrt(N)")]
    for counts, p, f, what in synthetic:
        values = [f(n) for n in counts]
        got = task("extrapolate", lambda: float(lab.extrapolate(list(counts), list(values), p)))
        if got is None:
            return None
        if not math.isclose(got, 0.3, rel_tol=1e-9):
            hint = which(got, extrapolation_mistakes(counts, values, p)) or \
                "Richardson on the last two runs, ratio sqrt(N2/N1), the given order"
            if not richardson_ok:
                hint += " (it may use your richardson: make Task 4 pass first)"
            failures.append(f"Task 6, extrapolate({counts}, {what}, order {p:g}): {got:.10g}, "
                            f"the limit is 0.3. {sentence(hint)}")
            return None

    # radkit's series: the floor's peak under the lamp, limit rho E F at the centre (B-3).
    limit = 0.5 * 1.0 * 4 * b3(0.5, 0.5, 1.0)
    got = task("extrapolate", lambda: float(lab.extrapolate(list(COUNTS), list(peaks), 2.0)))
    if got is None:
        return None
    if abs(got - limit) > RICHARDSON_TOLERANCE:
        hint = which(got, extrapolation_mistakes(COUNTS, peaks, 2.0))
        failures.append(f"Task 6, extrapolate on radkit's peak radiosity of "
                        f"data/parallel-squares.json at {COUNTS} patches: {got:.10f}; Howell B-3 "
                        f"gives the limit {limit:.10f}, and Richardson from the last two runs "
                        f"should be within {RICHARDSON_TOLERANCE:g} of it (its O(h⁴) remainder, "
                        f"measured {RICHARDSON_MEASURED:g}). {sentence(hint) if hint else ''}"
                        .strip())
        return None
    return limit, got


def check(student_dir, radkit=None):
    radkit = need_radkit(radkit, 2)
    lab = load_student(student_dir, "meshing.py")
    failures = []

    task = guarded(failures, TASK_OF)

    with tempfile.TemporaryDirectory() as tmp:
        runs = {n: Path(tmp) / f"parallel-{n}" for n in COUNTS}
        for n, out in runs.items():
            run_radkit(radkit, "run", data_file("parallel-squares.json"), "--patches", n,
                       "--tol", "1e-10", "--seed", 1, "--threads", 2, "--no-render", "--out", out)
        peaks = [read_run(runs[n], "lower")[1] for n in COUNTS]
        check_reading(lab, task, failures, runs[32],
                      {s: read_run(runs[32], s) for s in ("lower", "upper")})

    check_point_limit(lab, task, failures)
    check_slope(lab, task, failures)
    richardson_ok = check_richardson(lab, task, failures)
    check_order(lab, task, failures)
    result = check_extrapolate(lab, task, failures, peaks, richardson_ok)
    if result and not failures:
        limit, got = result
        print(f"lab 2: the peak at {COUNTS[-1]} patches is {limit - peaks[-1]:.2e} W/m² below the "
              f"B-3 limit, your Richardson estimate {got - limit:+.1e}")
    return failures
