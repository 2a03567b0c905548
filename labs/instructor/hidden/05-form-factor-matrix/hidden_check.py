"""Hidden cases for lab 5 (labs/grade.py runs them besides check_lab.py): a hand-made matrix
with unequal areas, patches of a surface not listed together, and light escaping. Oracles:
values worked by hand below (row sums, A_i F_ij sums, pair differences).

Catches what the public cases (the cube's equal patches, whose F is symmetric, so its column
sums equal its row sums) miss: a row_deficit from the column sums, 1 - F.sum(axis=0); and
surface_factors that assume a surface's patches come one after the other."""
import math

import numpy as np

from pyradkit import guarded, load_student

TASK_OF = {"surface_factors": 1, "row_deficit": 2, "reciprocity_error": 3}
# Patches 0 and 2 form surface 1, patch 1 is surface 0; areas 2, 1, 1.
F = np.array([[0.0, 0.25, 0.5], [0.5, 0.0, 0.25], [0.5, 0.5, 0.0]])
AREA = np.array([2.0, 1.0, 1.0])
SURFACE = np.array([1, 0, 1])
# F_01 = (0.5 + 0.25) / 1; F_10 = (2 * 0.25 + 1 * 0.5) / 3; F_11 = (2 * 0.5 + 1 * 0.5) / 3.
SURFACE_F = np.array([[0.0, 0.75], [1 / 3, 0.5]])
DEFICIT = np.array([0.25, 0.25, 0.0])  # 1 - row sums; the column sums give 0, 0.25, 0.25
# A_i F_ij against A_j F_ji: (0.5, 0.5), (1.0, 0.5), (0.25, 0.5): |diff| / max = 0, 0.5, 0.5;
# sum |diff| / sum of both = (0 + 0.5 + 0.25) / (1 + 1.5 + 0.75).
RECIPROCITY = (0.5, 0.75 / 3.25)


def check(student_dir, radkit=None):
    lab = load_student(student_dir, "matrix.py")
    failures = []
    task = guarded(failures, TASK_OF)

    got = task("surface_factors", lambda: np.asarray(
        lab.surface_factors(F.copy(), AREA.copy(), SURFACE.copy()), dtype=float))
    if got is not None and not (got.shape == SURFACE_F.shape and np.allclose(got, SURFACE_F)):
        failures.append(f"Task 1 (hidden case): surface_factors with surface 1 made of patches 0 "
                        f"and 2 (areas 2 and 1) and surface 0 of patch 1 gave {got.tolist()}, "
                        f"not {SURFACE_F.tolist()}: group the patches by their surface id, "
                        "wherever they are listed.")
    got = task("row_deficit", lambda: np.asarray(lab.row_deficit(F.copy()), dtype=float))
    if got is not None and not (got.shape == DEFICIT.shape and np.allclose(got, DEFICIT)):
        failures.append(f"Task 2 (hidden case): row_deficit of a matrix whose rows sum to 0.75, "
                        f"0.75 and 1 gave {got.tolist()}, not {DEFICIT.tolist()}: one minus "
                        "each ROW's sum (F is not symmetric when areas differ).")
    got = task("reciprocity_error", lambda: tuple(map(float, lab.reciprocity_error(
        F.copy(), AREA.copy()))))
    if got is not None and not all(math.isclose(g, w, rel_tol=1e-12)
                                   for g, w in zip(got, RECIPROCITY)):
        failures.append(f"Task 3 (hidden case): reciprocity_error of a 3-patch matrix gave "
                        f"{got}, not ({RECIPROCITY[0]:.6g}, {RECIPROCITY[1]:.6g}) worked by "
                        "hand from A_i F_ij against A_j F_ji.")
    return failures
