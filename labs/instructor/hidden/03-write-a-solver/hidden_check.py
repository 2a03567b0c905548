"""Hidden cases for lab 3 (labs/grade.py runs them besides check_lab.py): small systems built to
have ties and channels that differ. Oracle: radkit's built-in southwell on the same system,
shot by shot (docs/solvers.md: it shoots the largest A_i sum_c Delta B_ic, the first on ties),
and the direct solution to convergence.

Catches what the public cases (grey two-patch systems, then the Cornell box, where no two
patches tie) miss: ties broken towards the last patch, and a choice by one channel's Delta B
(a patch with a blue emitter is never shot first)."""
import numpy as np

from pyradkit import guarded, import_radkit, load_student

TASK_OF = {"Southwell.step": "1 or 2"}


def systems(rk):
    """(what, System): four patches in a symmetric enclosure, two emitters of equal power."""
    F = np.full((4, 4), 0.25)  # a closed enclosure of equal patches sees each one equally
    area = np.ones(4)
    rho = np.array([[0.5, 0.5, 0.5], [0.2, 0.6, 0.9], [0.7, 0.3, 0.1], [0.4, 0.4, 0.8]])
    tie = rk.System(F, area, rho, np.array([[0, 0, 0], [1.0, 1, 1], [0, 0, 0], [1.0, 1, 1]]))
    blue = rk.System(F, area, rho, np.array([[0.5, 0, 0], [0, 0, 0], [0, 0, 3.0], [0, 0, 0]]))
    return [("two equal emitters (patches 2 and 4 tie)", tie),
            ("a red emitter of power 0.5 and a blue one of power 3", blue)]


def check(student_dir, radkit=None):
    rk = import_radkit(3)
    student = load_student(student_dir, "southwell.py")
    failures = []
    task = guarded(failures, TASK_OF)
    for what, system in systems(rk):
        for shots in range(1, 9):
            solver = task("Southwell.step", lambda: student.Southwell())
            mine = solver and task("Southwell.step", lambda: rk.solve(
                system, solver, tolerance=1e-15, max_iterations=shots))
            if mine is None:
                return failures
            builtin = rk.solve(system, "southwell", tolerance=1e-15, max_iterations=shots)
            if not np.allclose(mine["radiosity"], builtin["radiosity"], rtol=1e-12, atol=1e-15):
                failures.append(f"Task 1 (hidden case): with {what}, your B differs from radkit's "
                                f"southwell after shot {shots}: shoot the patch with the largest "
                                "A_i * (sum over the three channels of Delta B_i), the first one "
                                "on ties.")
                break
    return failures
