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
from pyradkit import data_file, guarded, import_radkit, load_student, sentence  # noqa: E402

# Both tasks live in step(), so an exception there is one or the other.
TASK_OF = {"Southwell.step": "1 or 2"}


def direct(F, rho, E):
    """Solves (I - rho F) B = E per channel: the closed form the iteration must reach."""
    n = len(F)
    return np.stack([np.linalg.solve(np.eye(n) - rho[:, c, None] * F, E[:, c]) for c in range(3)],
                    axis=1)


def grey(values):
    return np.repeat(np.asarray(values, dtype=float)[:, None], 3, axis=1)


def diagnose(B, F, A, rho, E):
    """Which usual mistake produces B, as a sentence (None when none matches). A slip that
    gives the right answer on this system (F symmetric, equal areas) is not named."""
    right = direct(F, rho, E)
    scale = np.abs(right).max()
    gap = np.abs(B - right).max() / scale
    if gap < 1e-5:
        return (f"B is right to {gap:.1g} of the largest B, the rounding of single precision: "
                "keep F, B and Delta B in float64 (a float32 copy of F or of B loses digits).")

    def close(X):
        return (np.allclose(B, X, rtol=1e-6, atol=1e-9)
                and not np.allclose(X, right, rtol=1e-6, atol=1e-9))
    if close(E):
        return ("B never changes from E: add what each patch receives to B as well as to its "
                "unshot Delta B.")
    if close(direct(F.T, rho, E)):
        return ("your B solves B = E + rho F^T B: you shot with F_ij where F_ji belongs. The light "
                "patch j receives from i is rho_j F_ji Delta B_i, and F_ji = F_ij A_i / A_j "
                "(reciprocity); it only looks right when all areas are equal.")
    # Shooting with the shooter's reflectance rho_i converges to B_j = E_j + sum_i F_ji rho_i B_i,
    # (I - F diag(rho)) B = E per channel: a closed form of the slip, no solver needed.
    n = len(F)
    if not np.allclose(rho, rho[:1]) and close(np.stack(
            [np.linalg.solve(np.eye(n) - F * rho[None, :, c], E[:, c]) for c in range(3)], axis=1)):
        return ("your B is what shooting with the shooter's reflectance rho_i gives: patch j "
                "reflects what it receives with its own reflectance, rho_j F_ji Delta B_i.")
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
    task = guarded(failures, TASK_OF)

    def run(system, **options):
        """rk.solve with a fresh student solver: (result, solver), or None after a failure."""
        solver = task("Southwell.step", lambda: student.Southwell())
        if solver is None:
            return None
        result = task("Southwell.step", lambda: rk.solve(system, solver, **options))
        return None if result is None else (result, solver)

    # 1. Two patches that see only each other: B1 = 1 + rho_1 B2, B2 = rho_2 B1, so
    #    B = (1, rho_2) / (1 - rho_1 rho_2) = (5/3, 4/3). Unequal reflectances tell rho_j
    #    (the receiver's, right) from rho_i (the shooter's: (5/3, 5/6)).
    F = np.array([[0.0, 1.0], [1.0, 0.0]])
    A, rho, E = np.ones(2), grey([0.5, 0.8]), grey([1.0, 0.0])
    system = rk.System(F, A, rho, E)
    done = run(system, tolerance=1e-12, max_iterations=5000)
    if done is None:
        return failures
    r = done[0]
    exact = grey([5 / 3, 4 / 3])
    if not np.allclose(r["radiosity"], exact, rtol=1e-10):
        hint = diagnose(r["radiosity"], F, A, rho, E)
        # Any order of shots reaches the same B here: a slip diagnose names is in the shot, but
        # a B stuck at E or no convergence may be a choice of a patch with nothing to shoot.
        stuck = hint is None or np.allclose(r["radiosity"], E)
        which = "Task 1 or 2" if stuck else "Task 2"
        if hint is None and not r["converged"]:
            hint = (f"it did not converge ({r['exit']}, residual {r['residual']:.3g} after "
                    f"{r['iterations']} shots): does each shot multiply by the receiver's "
                    "reflectance rho_j, and does the shooter's Delta B go to zero?")
        failures.append(f"{which}, two facing patches (rho = 0.5 and 0.8): B = "
                        f"{r['radiosity'][:, 0]} "
                        f"where the closed form is (5/3, 4/3). {sentence(hint) if hint else ''}"
                        .strip())
        return failures
    # sweeps() is shots / n: a step that does not count its shot reports no work at all.
    sweeps = r["history"]["sweeps"][-1]
    if not np.isclose(sweeps, r["iterations"] / 2, rtol=1e-12):
        failures.append(f"Task 2, two facing patches: after {r['iterations']} shots your "
                        f"solver reports {sweeps:g} sweeps, not {r['iterations']}/2: step() must "
                        "add 1 to self.shots for every shot (sweeps() divides it by n).")

    # 2. A small patch (A = 1) inside an enclosure (A = 4) that sees itself: F_12 = 1,
    #    F_21 = A1/A2 = 1/4, F_22 = 3/4. Then B2 = B1/5 and B1 = 1 + B2/2: (10/9, 2/9).
    F = np.array([[0.0, 1.0], [0.25, 0.75]])
    A, rho = np.array([1.0, 4.0]), grey([0.5, 0.5])
    system = rk.System(F, A, rho, E)
    done = run(system, tolerance=1e-12, max_iterations=5000)
    if done is None:
        return failures
    r, _ = done
    if not np.allclose(r["radiosity"], grey([10 / 9, 2 / 9]), rtol=1e-10):
        hint = diagnose(r["radiosity"], F, A, rho, E)
        # The facing patches passed, so the choice works; only the shot can differ here.
        failures.append(f"Task 2, patch inside an enclosure (unequal areas, F_22 = 3/4): B = "
                        f"{r['radiosity'][:, 0]} where the closed form is (10/9, 2/9). "
                        f"{sentence(hint) if hint else SELF_SHOT_HINT}".strip())

    # 3. The order of shots, on a scene where areas differ: after k shots B must equal the
    #    built-in southwell's after k shots (same choice rule, same arithmetic up to rounding).
    scene = rk.load_scene(str(data_file("cornell-box.json")))
    mesh = rk.mesh(scene, patches=150)
    cornell = rk.System(rk.form_factors(mesh))
    k = 60
    done = run(cornell, tolerance=1e-15, max_iterations=k)
    if done is None:
        return failures
    ours = done[0]
    theirs = rk.solve(cornell, "southwell", tolerance=1e-15, max_iterations=k)
    scale = np.abs(theirs["radiosity"]).max()
    if ours["iterations"] != k:
        failures.append(f"Task 1 or 2, Cornell box: your solver stopped after "
                        f"{ours['iterations']} of {k} shots ({ours['reason']}).")
    elif not np.allclose(ours["radiosity"], theirs["radiosity"], rtol=1e-9, atol=1e-12 * scale):
        first, gap = None, 0.0
        for j in range(1, k + 1):
            done = run(cornell, tolerance=1e-15, max_iterations=j)
            if done is None:
                return failures
            mine = done[0]["radiosity"]
            builtin = rk.solve(cornell, "southwell", tolerance=1e-15, max_iterations=j)["radiosity"]
            if not np.allclose(mine, builtin, rtol=1e-9, atol=1e-12 * scale):
                first, gap = j, float(np.abs(mine - builtin).max() / scale)
                break
        # Named after the likelier cause: Task 1 (the choice) only once the shot is right.
        which = "Task 2"
        if failures:
            why = "fix the failures above first: this test builds on them"
        elif gap < 1e-5:
            # Same patch, same shot, to single precision: the arithmetic lost digits.
            why = (f"B agrees to {gap:.1g} of the largest B, the rounding of single precision: "
                   "keep F, B and Delta B in float64 (a float32 copy of F or of B loses the "
                   "digits the driver's residual measures)")
        else:
            which = "Task 1"
            why = ("the earlier tests passed, so the choice of patch differs: shoot the largest "
                   "unshot POWER A_i * sum_c Delta B_ic (not the largest Delta B, which ignores "
                   "that a big patch carries more light), the first one on ties")
        failures.append(f"{which}, Cornell box: after {k} shots your B differs from the built-in "
                        f"southwell's; the first difference is at shot {first}: {why}.")

    # 4. To convergence: B - B* = (I - rho F)^-1 r, so |B - B*| <= |r| / (1 - max rho * max row
    #    sum of F) with |r| <= tolerance * |E| as the driver measures it.
    tol = 1e-6
    done = run(cornell, tolerance=tol, max_iterations=200000)
    if done is None:
        return failures
    r = done[0]
    reference = direct(cornell.F, cornell.reflectance, cornell.emission)
    contraction = cornell.reflectance.max() * cornell.F.sum(axis=1).max()
    bound = tol * np.abs(cornell.emission).max() / (1 - contraction)
    error = np.abs(r["radiosity"] - reference).max()
    if not r["converged"]:
        failures.append(f"Task 1 or 2, Cornell box: no convergence to {tol} ({r['exit']}: "
                        f"{r['reason']}).")
    elif error > bound:
        failures.append(f"Task 2, Cornell box: converged, but B is {error:.3g} W/m^2 from the "
                        f"direct solution, more than the {bound:.3g} its residual allows.")
    elif not failures:
        sweeps = r["history"]["sweeps"][-1]
        print(f"lab 3: Cornell box ({len(mesh)} patches) to {tol}: {r['iterations']} shots = "
              f"{sweeps:.2f} sweeps, |B - B*| = {error:.2g} W/m^2 (bound {bound:.2g})")
    return failures
