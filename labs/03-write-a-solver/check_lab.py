"""Check for lab 3: a Southwell (progressive refinement) solver written in Python.

Runs the student's Southwell class through radkit.solve (which measures the true residual from F
after every shot) on systems with closed-form solutions, against the built-in southwell shot by
shot, and to convergence on the Cornell box. When an answer is wrong it compares it with what
the usual mistakes produce, and says which one it was.
"""
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from pyradkit import data_file, import_radkit, load_student  # noqa: E402


def direct(F, rho, E):
    """Solves (I - rho F) B = E per channel: the closed form the iteration must reach."""
    n = len(F)
    return np.stack([np.linalg.solve(np.eye(n) - rho[:, c, None] * F, E[:, c]) for c in range(3)],
                    axis=1)


def grey(values):
    return np.repeat(np.asarray(values, dtype=float)[:, None], 3, axis=1)


def diagnose(B, F, A, rho, E):
    """Which usual mistake produces B, as a sentence (None when none matches)."""
    close = lambda X: np.allclose(B, X, rtol=1e-6, atol=1e-9)  # noqa: E731
    if close(E):
        return ("B never changes from E: add what each patch receives to B as well as to its "
                "unshot Delta B.")
    if close(direct(F.T, rho, E)):
        return ("your B solves B = E + rho F^T B: you shot with F_ij where F_ji belongs. The light "
                "patch j receives from i is rho_j F_ji Delta B_i, and F_ji = F_ij A_i / A_j "
                "(reciprocity); it only looks right when all areas are equal.")
    if close(direct(F - np.diag(np.diag(F)), rho, E)):
        return ("your B is what you get with F_ii = 0: the light a patch sends to itself (a "
                "concave patch, or here an enclosure) is lost. Set Delta B_i = 0 before "
                "distributing, so what i receives from its own shot stays to be shot.")
    bad_area = F * A[None, :] / A[:, None]  # F_ji = F_ij A_j / A_i: the ratio upside down
    if close(direct(bad_area.T, rho, E)):
        return "reciprocity upside down: F_ji = F_ij A_i / A_j, not F_ij A_j / A_i."
    return None


# The two facing patches passed, so the shot is right wherever no patch sees itself.
SELF_SHOT_HINT = ("Your solver is right on the two facing patches, where F_ii = 0, so look at "
                  "j = i: the enclosure receives part of its own shot (rho_2 F_22 Delta B_2). "
                  "Take Delta B_i, set it to 0, then distribute, so that part stays to be shot "
                  "(zeroing after the loop throws it away).")


def check(student_dir, radkit_binary=None):
    rk = import_radkit(3)
    student = load_student(student_dir, "southwell.py")
    failures = []

    def run(system, **options):
        return rk.solve(system, student.Southwell(), **options)

    # 1. Two patches that see only each other: B1 = 1 + B2/2, B2 = B1/2, so (4/3, 2/3).
    F = np.array([[0.0, 1.0], [1.0, 0.0]])
    A, rho, E = np.ones(2), grey([0.5, 0.5]), grey([1.0, 0.0])
    system = rk.System(F, A, rho, E)
    try:
        r = run(system, tolerance=1e-12, max_iterations=5000)
    except NotImplementedError as e:
        return [f"not done yet: {e}"]
    exact = grey([4 / 3, 2 / 3])
    if not np.allclose(r["radiosity"], exact, rtol=1e-10):
        hint = diagnose(r["radiosity"], F, A, rho, E)
        if hint is None and not r["converged"]:
            hint = (f"it did not converge ({r['exit']}, residual {r['residual']:.3g} after "
                    f"{r['iterations']} shots): does each shot multiply by the receiver's "
                    "reflectance rho_j, and does the shooter's Delta B go to zero?")
        failures.append(f"two facing patches: B = {r['radiosity'][:, 0]} where the closed form "
                        f"is (4/3, 2/3). {hint or ''}".strip())
        return failures

    # 2. A small patch (A = 1) inside an enclosure (A = 4) that sees itself: F_12 = 1,
    #    F_21 = A1/A2 = 1/4, F_22 = 3/4. Then B2 = B1/5 and B1 = 1 + B2/2: (10/9, 2/9).
    F = np.array([[0.0, 1.0], [0.25, 0.75]])
    A = np.array([1.0, 4.0])
    system = rk.System(F, A, rho, E)
    r = run(system, tolerance=1e-12, max_iterations=5000)
    if not np.allclose(r["radiosity"], grey([10 / 9, 2 / 9]), rtol=1e-10):
        hint = diagnose(r["radiosity"], F, A, rho, E)
        failures.append("patch inside an enclosure (unequal areas, F_22 = 3/4): B = "
                        f"{r['radiosity'][:, 0]} where the closed form is (10/9, 2/9). "
                        f"{hint or SELF_SHOT_HINT}".strip())

    # 3. The order of shots, on a scene where areas differ: after k shots B must equal the
    #    built-in southwell's after k shots (same choice rule, same arithmetic up to rounding).
    scene = rk.load_scene(str(data_file("cornell-box.json")))
    mesh = rk.mesh(scene, patches=150)
    cornell = rk.System(rk.form_factors(mesh))
    k = 60
    ours = run(cornell, tolerance=1e-15, max_iterations=k)
    theirs = rk.solve(cornell, "southwell", tolerance=1e-15, max_iterations=k)
    scale = np.abs(theirs["radiosity"]).max()
    if ours["iterations"] != k:
        failures.append(f"Cornell box: your solver stopped after {ours['iterations']} of {k} "
                        f"shots ({ours['reason']}).")
    elif not np.allclose(ours["radiosity"], theirs["radiosity"], rtol=1e-9, atol=1e-12 * scale):
        first = next(j for j in range(1, k + 1)
                     if not np.allclose(run(cornell, tolerance=1e-15, max_iterations=j)["radiosity"],
                                        rk.solve(cornell, "southwell", tolerance=1e-15,
                                                 max_iterations=j)["radiosity"],
                                        rtol=1e-9, atol=1e-12 * scale))
        failures.append(
            f"Cornell box: after {k} shots your B differs from the built-in southwell's; the first "
            f"difference is at shot {first}. If the earlier tests passed, the choice of patch "
            "differs: shoot the largest unshot POWER A_i * sum_c Delta B_ic (not the largest "
            "Delta B, which ignores that a big patch carries more light), the first one on ties.")

    # 4. To convergence: B - B* = (I - rho F)^-1 r, so |B - B*| <= |r| / (1 - max rho * max row
    #    sum of F) with |r| <= tolerance * |E| as the driver measures it.
    tol = 1e-6
    r = run(cornell, tolerance=tol, max_iterations=200000)
    reference = direct(cornell.F, cornell.reflectance, cornell.emission)
    contraction = cornell.reflectance.max() * cornell.F.sum(axis=1).max()
    bound = tol * np.abs(cornell.emission).max() / (1 - contraction)
    error = np.abs(r["radiosity"] - reference).max()
    if not r["converged"]:
        failures.append(f"Cornell box: no convergence to {tol} ({r['exit']}: {r['reason']}).")
    elif error > bound:
        failures.append(f"Cornell box: converged, but B is {error:.3g} W/m^2 from the direct "
                        f"solution, more than the {bound:.3g} its residual allows.")
    else:
        sweeps = r["history"]["sweeps"][-1]
        print(f"lab 3: Cornell box ({len(mesh)} patches) to {tol}: {r['iterations']} shots = "
              f"{sweeps:.2f} sweeps, |B - B*| = {error:.2g} W/m^2 (bound {bound:.2g})")
    return failures
