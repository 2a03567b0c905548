"""Check for lab 1: form factors by hand (formfactor.py).

Oracles, from Howell, "A Catalog of Radiation Heat Transfer Configuration Factors"
(docs/oracles.md):
- B-3, a point under one corner of a parallel rectangle. Summed with signs over the four corners
  it is the exact factor from any point of a parallel plane to a rectangle, so it also gives the
  exact value of any quadrature rule on parallel rectangles: the student's rule is checked to
  rounding, not to a tolerance.
- C-11 (parallel opposed rectangles) and C-14 (perpendicular, common edge) as values: the
  catalogue's table, and a few evaluated once to 17 digits (mpmath) and written down here. The
  check holds no copy of a formula a task asks for (no contour sum, no C-11 or C-14): it names
  a slip from how the student's own values behave (a ratio, a growth with size, a normal that
  is ignored).
- The summation rule: the five faces of a cube, seen from a point of the sixth, fill its
  hemisphere, so their factors sum to exactly 1, and the four walls to 1 minus the top's B-3.
radkit formfactors is the reference for the pair with no closed form (tilted-pair.json).

Tolerances: where the check knows the rule's exact value, rounding only (1e-10 relative).
Against a closed form, ten times the error the reference solution's n x n rule measures there
(listed with each case), and never below 1e-9. Every mistake listed in README.md moves the answer
by tens of percent or more, at least a thousand times the tolerance.
"""
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from pyradkit import (guarded, howell_b3 as b3, load_student, need_radkit,  # noqa: E402
                      radkit_surface_factors, sentence)

LAB = Path(__file__).resolve().parent
ROUNDING = 1e-10  # relative: two evaluations of the same formula or the same rule
TASK_OF = {"point_to_polygon": 1, "gauss_legendre_rule": 2, "form_factor": 3, "howell_c11": 4,
           "howell_c14": 4, "near_field_errors": 5}


def rect(x0, x1, y0, y1, z, down=False):
    """The rectangle [x0, x1] x [y0, y1] at height z, counter-clockwise seen from its front:
    facing up (+z), or down."""
    corners = [[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]]
    return np.array(corners[::-1] if down else corners, dtype=float)


FLOOR = rect(0, 1, 0, 1, 0)
WALL_2 = np.array([[0, 0, 0], [0, 0, 2], [1, 0, 2], [1, 0, 0]], dtype=float)  # 1 x 2, facing +y
PANEL = np.array([[0.25, 1.5, 0.2], [1.25, 1.5, 0.2], [1.25, 1.02, 0.84], [0.25, 1.02, 0.84]])


# --- the oracles -------------------------------------------------------------------------------
def point_under(px, py, x0, x1, y0, y1, h):
    """Exact factor from (px, py) facing up to the rectangle [x0, x1] x [y0, y1] h above."""
    return (b3(x1 - px, y1 - py, h) - b3(x0 - px, y1 - py, h)
            - b3(x1 - px, y0 - py, h) + b3(x0 - px, y0 - py, h))


# Howell's closed forms, as values (the formulas are Task 4): the catalogue's tabulated
# values (docs/oracles.md) with half a unit of their last digit, and C-11 at X = Y = 1 and
# C-14 at W = H = 1 to 17 digits.
C11_TABLE = [((1, 1, 1), 0.19982489569838746, 1e-15), ((0.5, 0.5, 1), 0.068590, 5e-7),
             ((2, 2, 1), 0.415253, 5e-7), ((1, 5, 1), 0.359167, 5e-7),
             ((1, 1.5, 0.5), 0.4755764365, 5e-11)]
C14_TABLE = [((1, 1, 1), 0.20004377607540316, 1e-15), ((1, 1, 2), 0.232853, 5e-7),
             ((1, 2, 1), 0.116426, 5e-7), ((1, 0.5, 0.5), 0.240636, 5e-7)]
# Closer than the catalogue prints, for the n = 8 rule's tolerances: C-11(1, 1.5, 0.5) and
# C-14(1, 1, 2), the closed forms of README.md evaluated once with mpmath at 30 digits.
C11_1_15_05 = 0.47557643653295292
C14_1_1_2 = 0.23285260279536189
# The exact value of the n x n Gauss-Legendre rule for F between the 1 x 1.5 rectangles 0.5
# apart: B-3 summed over the corners (point_under) at the rule's nodes, weighted. Evaluated
# once with mpmath at 30 digits (Legendre nodes as roots of P_n).
GL_RULE_1_15_05 = {2: 0.48157640308898528, 5: 0.47561908416401444}
# Unit squares d apart: C-11(1, 1, d) and the relative error of the 2 x 2 rule against it,
# evaluated once the same way.
NEAR_FIELD = [(1.0, 0.19982489569838738, 0.0072509322053159718),
              (0.5, 0.41525328357714674, 0.0022149857090046655),
              (0.25, 0.63203643001386029, 0.05479191606873384),
              (0.1, 0.82699452239725658, 0.099525963306670421)]


def integrate_x5y5(points, weights):
    p = np.asarray(points, dtype=float)
    return float(np.asarray(weights, dtype=float) @ (p[:, 0] ** 5 * p[:, 1] ** 5))


# --- what the usual mistakes give ----------------------------------------------------------------
def contour_slip(lab, task):
    """The contour-sum slip that scales with the polygon's size, or None. The check carries no
    contour sum of its own: it measures how the student's error grows as a square shrinks.
    Under a square of side s, 1 above, F ~ s²/π; leaving out γ_k leaves a sum ~ s (ratio to F
    ~ 1/s), not dividing by |v_k × v_k+1| = sin γ_k ~ s adds a factor s (ratio ~ s)."""
    up = np.array([0.0, 0.0, 1.0])
    ratios = []
    for s in (1e-2, 1e-3):
        got = task("point_to_polygon", lambda: float(lab.point_to_polygon(
            np.zeros(3), up, rect(-s / 2, s / 2, -s / 2, s / 2, 1.0, down=True))))
        if got is None or got == 0 or not math.isfinite(got):
            return None
        ratios.append(got / point_under(0, 0, -s / 2, s / 2, -s / 2, s / 2, 1.0))
    growth = ratios[0] / ratios[1]  # 10 when the error is ~ s, 0.1 when ~ 1/s
    if 0.05 < growth < 0.2:
        return ("you summed n·(v_k × v_k+1)/|v_k × v_k+1| without the angle γ_k: each edge "
                "counts γ_k times its unit normal (your error grows like 1/size as a square "
                "shrinks)")
    if 5 < growth < 20:
        return ("the edge's normal v_k × v_k+1 must be divided by its length |v_k × v_k+1| "
                "(= sin γ_k): your value falls like size³, not size², as a square shrinks")
    return None


RATIO_MISTAKES = [
    (2 * math.pi, "your value is 2π times the expected one: did you forget the 1/(2π)?"),
    (2.0, "your value is twice the expected one: the factor is 1/(2π), not 1/π"),
    (180 / math.pi, "your value is 180/π = 57.3 times the expected one: the angle γ_k is in "
                    "degrees; use radians (numpy.arccos and numpy.arctan2 return them)"),
    (360.0, "your value is 360 times the expected one: degrees and no 1/(2π)?"),
    (-1.0, "your value has the wrong sign: the sum is negative when the polygon faces x (its "
           "vertices, counter-clockwise seen from its front, run clockwise seen from x). Take "
           "the absolute value, or sum over the vertices in the other order"),
    (1 / (2 * math.pi), "your value is 1/(2π) of the expected one: the 1/(2π) is applied twice"),
]


def diagnose_ratio(got, exact):
    """A sentence naming the mistake when got/exact is one of the telltale factors."""
    if exact == 0 or not math.isfinite(got):
        return None
    return next((text for factor, text in RATIO_MISTAKES
                 if math.isclose(got / exact, factor, rel_tol=1e-6)), None)


# --- the tasks -----------------------------------------------------------------------------------
def check_point_to_polygon(lab, task, failures):
    up = np.array([0.0, 0.0, 1.0])
    square = rect(0, 1, 0, 1, 1, down=True)
    strip = rect(-0.5, 1.5, 0.1, 0.6, 0.3, down=True)
    on_square = (0, 1, 0, 1, 1.0)
    cases = [((0.5, 0.5, 0), square, on_square, "under the centre of a unit square 1 above"),
             ((0.0, 0.0, 0), square, on_square, "under a corner of that square (B-3 itself)"),
             ((0.2, 0.7, 0), square, on_square, "under the square, off centre"),
             ((1.6, -0.3, 0), square, on_square, "beside the square, outside its shadow"),
             ((0.3, 0.2, 0), strip, (-0.5, 1.5, 0.1, 0.6, 0.3), "under a 2 x 0.5 strip 0.3 above")]
    for x, polygon, (x0, x1, y0, y1, h), where in cases:
        got = task("point_to_polygon", lambda: float(lab.point_to_polygon(
            np.array(x, dtype=float), up, polygon.copy())))
        if got is None:
            return False
        exact = point_under(x[0], x[1], x0, x1, y0, y1, h)
        if not math.isclose(got, exact, rel_tol=ROUNDING):
            hint = diagnose_ratio(got, exact) or contour_slip(lab, task)
            failures.append(f"Task 1, point_to_polygon from a point {where}: {got:.10g}, Howell "
                            f"B-3 gives {exact:.10g}. "
                            f"{sentence(hint or 'compare with the formula in README.md')}")
            return False

    # Summation rule: from (0.3, 0.6, 0) on the floor of the unit cube the other five faces
    # (each counter-clockwise seen from inside) cover the hemisphere: their sum is 1, so the
    # four walls sum to 1 minus the top's B-3 value. The walls test x's normal: with the
    # polygon's normal in its place the five still sum to 1 (solid angles over 2π).
    top = rect(0, 1, 0, 1, 1, down=True)
    walls = [np.array([[0, 0, 0], [0, 0, 1], [1, 0, 1], [1, 0, 0]], dtype=float),
             np.array([[0, 1, 0], [1, 1, 0], [1, 1, 1], [0, 1, 1]], dtype=float),
             np.array([[0, 0, 0], [0, 1, 0], [0, 1, 1], [0, 0, 1]], dtype=float),
             np.array([[1, 0, 0], [1, 0, 1], [1, 1, 1], [1, 1, 0]], dtype=float)]
    x = np.array([0.3, 0.6, 0.0])
    for faces, exact, what in (([top] + walls, 1.0, "the five faces of a unit cube seen from a "
                                "point on the sixth sum to {total:.10g}; they fill the "
                                "hemisphere, so the sum is exactly 1 (Nusselt's analogy)"),
                               (walls, 1 - point_under(0.3, 0.6, 0, 1, 0, 1, 1.0),
                                "the four walls of a unit cube seen from a point on its floor "
                                "sum to {total:.10g}; with the top (Howell B-3) they fill the "
                                "hemisphere, so the sum is exactly {exact:.10g}")):
        total = task("point_to_polygon", lambda: sum(
            float(lab.point_to_polygon(x.copy(), up, f.copy())) for f in faces))
        if total is None:
            return False
        if not math.isclose(total, exact, rel_tol=ROUNDING):
            # A value that ignores the normal it is given used some other normal.
            tilted = np.array([0.6, 0.0, 0.8])
            same = task("point_to_polygon", lambda: math.isclose(
                float(lab.point_to_polygon(x.copy(), up, walls[0].copy())),
                float(lab.point_to_polygon(x.copy(), tilted, walls[0].copy())), rel_tol=1e-12))
            hint = ("your value does not change when x's normal does: you used the polygon's "
                    "normal, but the cosine at x needs x's own normal n (the walls are "
                    "perpendicular to it)" if same else
                    "each face's term must use the normal at x, and every face lies in front "
                    "of x, so no clipping is needed")
            failures.append(f"Task 1, point_to_polygon: {what.format(total=total, exact=exact)}. "
                            f"{sentence(hint)}")
            return False
    return True


def check_gauss_legendre_rule(lab, task, failures):
    para = np.array([[1, 0, 0.2], [3, 0, 0.2], [3.5, 1.5, 0.2], [1.5, 1.5, 0.2]])  # area 3
    rule = task("gauss_legendre_rule", lambda: lab.gauss_legendre_rule(para.copy(), 3))
    if rule is None:
        return False
    points, weights = (np.asarray(r, dtype=float) for r in rule)
    problem = None
    if points.shape != (9, 3) or weights.shape != (9,):
        problem = (f"for n = 3 it returned points of shape {points.shape} and weights of shape "
                   f"{weights.shape}; expected (9, 3) and (9,): n x n points in 3-D")
    elif not math.isclose(weights.sum(), 3.0, rel_tol=1e-12):
        s = weights.sum()
        fix = ("They sum to 4 A: Gauss-Legendre weights on [-1, 1] sum to 2 per direction; halve "
               "them when mapping to [0, 1]" if math.isclose(s, 12, rel_tol=1e-9) else
               "Multiply by the Jacobian |e1 × e2|, the area" if math.isclose(s, 1, rel_tol=1e-9)
               else "Check the mapping of the weights")
        problem = (f"the weights sum to {s:.6g} on a parallelogram of area 3; they must sum to "
                   f"its area (∫ 1 dA = A). {fix}")
    else:
        # Inside the parallelogram: parameters (u, v) of P0 + u e1 + v e2 in (0, 1).
        uv = np.linalg.lstsq(np.stack([para[1] - para[0], para[3] - para[0]], axis=1),
                             (points - para[0]).T, rcond=None)[0]
        if uv.min() <= 0 or uv.max() >= 1 or not np.allclose(points[:, 2], 0.2):
            problem = ("some points lie outside the parallelogram: map the Gauss-Legendre nodes "
                       "t in [-1, 1] to u = (t + 1)/2, then x = P0 + u e1 + v e2")
    if problem is None:
        # Degree 5 in each variable is exact with 3 points per direction (2n - 1).
        got = task("gauss_legendre_rule",
                   lambda: integrate_x5y5(*lab.gauss_legendre_rule(rect(1, 3, 0, 0.5, 0), 3)))
        if got is None:
            return False
        exact = (3 ** 6 - 1) / 6 * 0.5 ** 6 / 6
        if not math.isclose(got, exact, rel_tol=1e-12):
            problem = (f"with n = 3 it integrates x^5 y^5 over [1, 3] x [0, 0.5] to {got:.10g}, "
                       f"not {exact:.10g}: n Gauss-Legendre points integrate degree 2n - 1 "
                       "exactly, evenly spaced points do not. Use "
                       "numpy.polynomial.legendre.leggauss(n)")
    if problem:
        failures.append(f"Task 2, gauss_legendre_rule: {problem}.")
        return False
    return True


def check_form_factor(lab, task, failures, radkit):
    def form_factor(pi, pj, n):
        return task("form_factor", lambda: float(lab.form_factor(pi.copy(), pj.copy(), n)))

    # C-11, a = 1, b = 1.5, c = 0.5: first the exact 2 x 2 and 5 x 5 rule values (B-3).
    lower, upper = rect(0, 1, 0, 1.5, 0), rect(0, 1, 0, 1.5, 0.5, down=True)
    for n in (2, 5):
        got = form_factor(lower, upper, n)
        if got is None:
            return False
        exact = GL_RULE_1_15_05[n]
        if not math.isclose(got, exact, rel_tol=ROUNDING):
            r = got / exact
            if math.isclose(r, 1.5, rel_tol=1e-6):
                hint = ("your value is A_i = 1.5 times the expected one: did you forget to divide "
                        "by the area of patch i? F_ij = (1/A_i) ∫ F_dA→j dA")
            elif math.isclose(r, 1 / 1.5, rel_tol=1e-6):
                hint = ("your value is 1/A_i times the expected one: the weights already carry "
                        "the area; divide their sum by A_i once")
            else:
                hint = diagnose_ratio(got, exact) or (
                    "integrate point_to_polygon(x, n_i, patch j) over patch i with your rule, "
                    "divided by A_i")
            failures.append(f"Task 3, form_factor between opposed 1 x 1.5 rectangles 0.5 apart "
                            f"with n = {n}: {got:.10g}; the {n} x {n} Gauss-Legendre rule gives "
                            f"exactly {exact:.10g} (Howell B-3 at its points). {sentence(hint)}")
            return False

    # Against the closed forms at n = 8: (patch i, patch j, exact, the reference rule's measured
    # relative error, what, the factor the other way round). Tolerance: ten times that error,
    # at least 1e-9. The wall-to-floor direction converges only algebraically (README.md).
    f12 = C14_1_1_2
    cases = [(lower, upper, C11_1_15_05, 3.5e-7, "C-11, 1 x 1.5 rectangles 0.5 apart", None),
             (FLOOR, WALL_2, f12, 7.2e-16, "C-14, from the 1 x 1 floor to the 1 x 2 wall", f12 / 2),
             (WALL_2, FLOOR, f12 / 2, 3.3e-4, "C-14, from the 1 x 2 wall to the 1 x 1 floor", f12)]
    for pi, pj, exact, measured, what, other in cases:
        tol = max(10 * measured, 1e-9)
        got = form_factor(pi, pj, 8)
        if got is None:
            return False
        if abs(got - exact) > tol * exact:
            if other is not None and math.isclose(got, other, rel_tol=1e-2):
                hint = ("that is the factor the other way round: F_12 and F_21 are mixed up. F_ij "
                        "is the share of the light leaving i that reaches j: integrate over patch "
                        "i (the first argument), divide by A_i; reciprocity A_i F_ij = A_j F_ji "
                        "relates the two")
            else:
                hint = diagnose_ratio(got, exact) or "see README.md, Task 3"
            failures.append(f"Task 3, form_factor ({what}, n = 8): {got:.10g}, Howell gives "
                            f"{exact:.10g} (tolerance {tol:.1g} relative; the 8 x 8 rule's own "
                            f"error here is {measured:.1g}). {sentence(hint)}")
            return False

    # A pair with no closed form: radkit's point-polygon F is within its tolerance 1e-6
    # (docs/formfactors.md) and printed to 10 digits; the 8 x 8 rule is within 1e-9 here.
    ref = radkit_surface_factors(radkit, LAB / "tilted-pair.json")
    polygons = {"floor": FLOOR, "panel": PANEL}
    for i, j in (("floor", "panel"), ("panel", "floor")):
        got = form_factor(polygons[i], polygons[j], 8)
        if got is None:
            return False
        if abs(got - ref[(i, j)]) > 2e-6:
            hint = ("that is radkit's F for the other direction: F_12 and F_21 are mixed up"
                    if abs(got - ref[(j, i)]) < 1e-4 else
                    "is the normal of patch i taken by the right-hand rule from its "
                    "counter-clockwise vertices?")
            failures.append(f"Task 3, form_factor on tilted-pair.json, F({i} → {j}) with n = 8: "
                            f"{got:.10f}; radkit formfactors gives {ref[(i, j)]:.10f} (within "
                            f"2e-6: its tolerance 1e-6 plus the rule's error). {sentence(hint)}")
            return False
    return True


def check_closed_forms(lab, task, failures):
    ok = True
    for name, table, names in (("howell_c11", C11_TABLE, "a, b, c"),
                               ("howell_c14", C14_TABLE, "l, w, h")):
        for args, value, tol in table:
            got = task(name, lambda: float(getattr(lab, name)(*map(float, args))))
            if got is None:
                ok = False
                break
            if not abs(got - value) <= max(tol, 1e-12 * value):
                hint = "compare it term by term with README.md (math.log is the natural logarithm)"
                # Swapping w and h gives the factor the other way, by reciprocity value w/h.
                if name == "howell_c14" and args[1] != args[2] and math.isclose(
                        got, value * args[1] / args[2], rel_tol=1e-5):
                    hint = ("that is the factor from the l x h rectangle: W = w/l belongs to A1, "
                            "the one the light leaves, H = h/l to A2")
                failures.append(f"Task 4, {name}({', '.join(f'{a:g}' for a in args)}) ({names}) "
                                f"= {got:.10g}; Howell's table: {value}. {sentence(hint)}")
                ok = False
                break
    return ok


def check_near_field(lab, task, failures, earlier_ok):
    distances = [d for d, _, _ in NEAR_FIELD]
    got = task("near_field_errors",
               lambda: np.asarray(lab.near_field_errors(list(distances), 2), dtype=float))
    if got is None:
        return None
    c = np.array([f for _, f, _ in NEAR_FIELD])
    exact = np.array([e for _, _, e in NEAR_FIELD])
    if got.shape != exact.shape or not np.allclose(got, exact, rtol=1e-8, atol=0):
        hint = "return |F_n - F| / F per distance, F from Howell C-11, F_n from form_factor(..., n)"
        if not earlier_ok:
            hint = "it uses form_factor and howell_c11: make Tasks 1 to 4 pass first"
        elif got.shape == exact.shape and np.allclose(got, exact * c, rtol=1e-6):
            hint = "those are absolute errors: divide by the exact F (relative error)"
        elif got.shape == exact.shape and np.allclose(np.abs(got), exact, rtol=1e-8):
            hint = "some are negative: return the size of the error, |F_n - F| / F"
        failures.append(f"Task 5, near_field_errors({distances}, n=2) = "
                        f"{np.array2string(got, precision=4)}; the 2 x 2 rule's errors are "
                        f"{np.array2string(exact, precision=4)} (its exact values from Howell "
                        f"B-3, against C-11). {sentence(hint)}")
        return None
    return exact


def check(student_dir, radkit=None):
    radkit = need_radkit(radkit, 1)
    lab = load_student(student_dir, "formfactor.py")
    failures = []

    task = guarded(failures, TASK_OF)

    basics = check_point_to_polygon(lab, task, failures)
    basics = check_gauss_legendre_rule(lab, task, failures) and basics
    if basics:
        integrated = check_form_factor(lab, task, failures, radkit)
    else:
        # Task 3 builds on Tasks 1 and 2: until they pass, only say whether it is written yet.
        integrated = False
        try:
            lab.form_factor(FLOOR.copy(), rect(0, 1, 0, 1, 1, down=True), 2)
        except NotImplementedError as e:
            if "Task 3" in str(e):
                failures.append(f"not done yet: {e}")
        except Exception:
            pass
    closed = check_closed_forms(lab, task, failures)
    errors = check_near_field(lab, task, failures, integrated and closed)
    if not failures:
        print(f"lab 1: the 2 x 2 rule is {errors[0]:.1e} off at d = 1 and {errors[-1]:.1e} at "
              "d = 0.1 (relative to C-11)")
    return failures
