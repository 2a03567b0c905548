"""Hidden cases for lab 4 (labs/grade.py runs them besides check_lab.py): other systems and
parameters. Oracles: radkit's Jacobi on two facing patches, whose iteration matrix has the
eigenvalues +-rho; matrices with known eigenvalues; Young's omega as the double root of
omega^2 rho^2 / 4 - omega + 1 = 0; sweep counts with a known minimum."""
import math

import numpy as np

from pyradkit import guarded, import_radkit, load_student

TASK_OF = {"convergence_factor": 1, "spectral_radius": 2, "young_omega": 3, "best_omega": 4}


def check(student_dir, radkit=None):
    rk = import_radkit(4)
    lab = load_student(student_dir, "analysis.py")
    failures = []
    task = guarded(failures, TASK_OF)

    # Task 1: a history that changes rate halfway, then radkit's own Jacobi run.
    sweeps = np.arange(41.0)
    residual = np.where(sweeps < 10, 0.5 ** sweeps, 0.5 ** 10 * 0.8 ** (sweeps - 10))
    got = task("convergence_factor",
               lambda: lab.convergence_factor({"sweeps": list(sweeps), "residual": list(residual)}))
    if got is not None and not math.isclose(got, 0.8, rel_tol=1e-9):
        failures.append(f"Task 1 (hidden case): a residual that falls by 0.5 per sweep for 10 "
                        f"sweeps, then by 0.8, gives {got}; the asymptotic factor is 0.8.")
    two = rk.System(np.array([[0.0, 1.0], [1.0, 0.0]]), np.ones(2), np.full(2, 0.6),
                    np.array([1.0, 0.0]))
    run = rk.solve(two, "jacobi", tolerance=1e-12)
    got = task("convergence_factor", lambda: lab.convergence_factor(run["history"]))
    if got is not None and not math.isclose(got, 0.6, rel_tol=1e-3):
        failures.append(f"Task 1 (hidden case): radkit's Jacobi on two facing patches of "
                        f"reflectance 0.6 converges by 0.6 per sweep; your factor is {got}.")

    # Task 2: (ones - I)/2 has eigenvalues 1, -1/2, -1/2; a small patch in an enclosure 1, -1/4.
    for F, rho, want in ((np.full((3, 3), 0.5) - 0.5 * np.eye(3),
                          np.array([[0.2, 0.7, 0.4]] * 3), 0.7),
                         (np.array([[0.0, 1.0], [0.25, 0.75]]),
                          np.array([[0.9, 0.5, 0.3], [0.5, 0.5, 0.5]]), None)):
        if want is None:  # diag(rho_c) F per channel: eigenvalues from the 2x2 closed form
            want = 0.0
            for c in range(3):
                M = rho[:, c, None] * F
                tr, det = np.trace(M), np.linalg.det(M)
                disc = math.sqrt(tr * tr / 4 - det)
                want = max(want, abs(tr / 2 + disc), abs(tr / 2 - disc))
        got = task("spectral_radius", lambda: lab.spectral_radius(F, rho))
        if got is not None and not math.isclose(got, want, rel_tol=1e-9):
            failures.append(f"Task 2 (hidden case): spectral_radius of a {len(F)}x{len(F)} system "
                            f"is {got}, not {want:.10g} (largest |eigenvalue| of rho_c F over "
                            "the channels).")

    # Task 3: the optimum is where omega^2 rho^2 / 4 - omega + 1 has its double root.
    for r in (0.3, 0.9, 0.99):
        got = task("young_omega", lambda: lab.young_omega(r))
        if got is None:
            break
        if not (1 <= got < 2 and abs(got * got * r * r / 4 - got + 1) < 1e-10):
            failures.append(f"Task 3 (hidden case): young_omega({r}) = {got} is not the double "
                            f"root of omega^2 rho^2 / 4 - omega + 1 in [1, 2).")
            break

    # Task 4: a known minimum, and a tie that the first omega wins.
    omegas = np.round(np.arange(1.0, 2.0, 0.05), 2)
    got = task("best_omega", lambda: lab.best_omega(lambda w: 5 + 100 * abs(w - 1.37), omegas))
    if got is not None and not math.isclose(got, 1.35):
        failures.append(f"Task 4 (hidden case): best_omega with fewest sweeps at omega 1.35 "
                        f"returned {got}.")
    table = {1.1: 9, 1.2: 4, 1.3: 4, 1.4: 7}
    got = task("best_omega", lambda: lab.best_omega(lambda w: table[float(w)], list(table)))
    if got is not None and not math.isclose(got, 1.2):
        failures.append(f"Task 4 (hidden case): two omegas tie for the fewest sweeps (1.2 and "
                        f"1.3): return the first, 1.2, not {got}.")
    return failures
