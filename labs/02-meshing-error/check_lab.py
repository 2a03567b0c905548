"""Check for lab 2: meshing error (meshing.py).

Oracles; the check holds no copy of what a task computes:
- radkit's own record of each run in files Task 1 does not read: the surface means in
  report.json ("surfaces") and the patch radiosities in radiosity.vtp (cell data "surface" and
  "radiosity"; docs/formats.md). The floor's peaks at 8 to 512 patches feed Task 6.
- Howell B-3 (docs/oracles.md) as values: the factor from a point under the centre of a parallel
  rectangle (four quarter rectangles) and B-3 of the whole rectangle, for the cases below,
  evaluated once with mpmath at 40 digits. The centre value gives the converged peak radiosity
  of data/parallel-squares.json's floor.
- Series built so that the answer is known without computing it: a power law's slope is its
  exponent; f = f* + C h^p has limit f* and order p. For the one series that is no power law, its
  least-squares slope and the usual wrong slopes, evaluated once with mpmath at 40 digits.

Tolerances: on the values and series rounding only (1e-9). On radkit's series, Richardson's
estimate keeps the next term of the error, O(h⁴). The reference solution measures it at 3.1e-6
from the runs at 128 and 512 patches (and at 2.0e-7 from 512 and 2048: a factor of 16 per halving
of h, as O(h⁴) predicts). The tolerance is 1e-5. The usual mistakes (the wrong exponent, no
extrapolation, the sign) leave 2.8e-4 or more.
"""
import json
import math
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from pyradkit import (data_file, guarded, load_student, need_radkit, run_radkit,  # noqa: E402
                      sentence, slope_hints, which)

SIGN_REASON = "the error falls as the patch count grows, so the slope is negative"

RICHARDSON_TOLERANCE = 1e-5
RICHARDSON_MEASURED = 3.1e-6  # the reference solution's remainder from 128 and 512 patches
COUNTS = [8, 32, 128, 512]    # two unit squares of k x k patches, k = 2, 4, 8, 16
TASK_OF = {"surface_radiosity": 1, "point_limit": 2, "loglog_slope": 3, "richardson": 4,
           "observed_order": 5, "extrapolate": 6}


# Howell B-3, evaluated once with mpmath at 40 digits: (a, b, h) -> (4 B-3(a/2, b/2, h), the
# factor from the point under the centre of the a x b rectangle; B-3(a, b, h), the factor from
# the point under one of its corners).
B3_VALUES = {(1.0, 1.0, 1.0): (0.23945647046077353883, 0.13853160599489299678),
             (2.0, 1.0, 0.5): (0.66950003965753506966, 0.22077762233476158560)}
# The floor's converged peak in data/parallel-squares.json: ρ E 4 B-3(1/2, 1/2, 1), ρ = 0.5, E = 1.
PEAK_LIMIT = 0.5 * B3_VALUES[(1.0, 1.0, 1.0)][0]

# Task 3's series at x = 8, 32, ..., 2048. For y = 0.3 x^-1.25 the slope is -1.25 and the
# swapped axes give 1/-1.25 by construction. The rest, least squares evaluated once with mpmath
# at 40 digits on the double-precision data: (slope, linear axes, log y against x, y against
# log x, swapped axes, end points).
SLOPE_SERIES = [
    (lambda x: 0.3 * x ** -1.25, "y = 0.3 x^-1.25",
     (-1.25, -4.7810963026291313e-6, -0.0026467313529445614, -0.0034891753053769917, -0.8,
      -1.25)),
    (lambda x: 0.02 / x * (1 + 3 / np.sqrt(x)), "y = 0.02/x (1 + 3/sqrt(x)), not a power",
     (-1.1167618387347662, -1.1151001171128789e-6, -0.0023227753094533079,
      -0.00080752616259692604, -0.8946156184003314, -1.1188131297265819)),
]


def radkit_results(run_dir):
    """{surface: (mean, peak)} red radiosity of a run, from report.json's surface means and
    radiosity.vtp's patches: radkit's own record, not the CSV files Task 1 reads."""
    run = Path(run_dir)
    report = json.loads((run / "report.json").read_text())
    means = {s["surface"]: float(s["radiosity_W_m2"][0]) for s in report["surfaces"]}
    cells = ET.parse(run / "radiosity.vtp").getroot().find("PolyData/Piece/CellData")
    arrays = {a.get("Name"): a.text.split() for a in cells.iter("DataArray")}
    surface = np.array(arrays["surface"], dtype=int)
    red = np.array(arrays["radiosity"], dtype=float)[0::3]
    return {name: (means[name], float(red[surface == k].max()))
            for k, name in enumerate(report["scene"]["surfaces"])}


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
    """expected: radkit_results of the run; the CSV files print the same doubles to 17 digits."""
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
                            f"radkit's report.json and radiosity.vtp say mean {mean:.10g}, peak "
                            f"{peak:.10g}. {sentence(hint)}")
            return False
    return True


def check_point_limit(lab, task, failures):
    for args in ((0.5, 1.0, 1.0, 1.0, 1.0), (0.8, 2.0, 2.0, 1.0, 0.5)):
        rho, e, a, b, h = args
        got = task("point_limit", lambda: float(lab.point_limit(*args)))
        if got is None:
            return False
        F, corner = B3_VALUES[(a, b, h)]
        exact = rho * e * F
        if not math.isclose(got, exact, rel_tol=1e-9):
            hint = which(got, [
                ("that is B-3 for the whole rectangle with its corner above the point: the point "
                 "is under the centre, so split the rectangle into four a/2 x b/2 ones, each with "
                 "a corner above the point, and add them (superposition)", rho * e * corner),
                ("that is one of the four quarter rectangles: add all four (multiply by 4)",
                 rho * e * F / 4),
                ("four corners of the full size: each quarter is a/2 x b/2",
                 rho * e * 4 * corner),
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
    for f, what, slopes in SLOPE_SERIES:
        y = f(x)
        got = task("loglog_slope", lambda: float(lab.loglog_slope(x.copy(), y.copy())))
        if got is None:
            return False
        exact = slopes[0]
        if not math.isclose(got, exact, rel_tol=1e-9):
            hint = which(got, slope_hints(*slopes, sign_reason=SIGN_REASON)) \
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
    limit = PEAK_LIMIT
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
        peaks = [radkit_results(runs[n])["lower"][1] for n in COUNTS]
        check_reading(lab, task, failures, runs[32], radkit_results(runs[32]))

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
