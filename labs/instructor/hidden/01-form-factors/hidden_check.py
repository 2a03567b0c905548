"""Hidden cases for lab 1 (labs/grade.py runs them besides check_lab.py): other geometry and
other parameters. Oracles: Howell B-3 summed over corners, which F keeps under any rotation of
point, normal and polygon together and which halves on each triangle of a square cut along its
diagonal seen from under its centre; Howell's C-11 and C-14, and the error of the 3 x 3 rule,
evaluated once with mpmath at 30 digits (Legendre nodes 0, +-sqrt(3/5)) and written down here.

Catches what the public cases (all with the normal along +z, all quadrilaterals) miss: a
point_to_polygon that takes the z component of the edge normals instead of their dot product
with the given normal, or that assumes four vertices; closed forms or errors tuned to the
public table."""
import math

import numpy as np

from pyradkit import guarded, howell_b3, load_student

TASK_OF = {"point_to_polygon": 1, "howell_c11": 4, "howell_c14": 4, "near_field_errors": 5}
C11 = [((3, 0.7, 1.3), 0.18523999407604505), ((0.4, 2.5, 0.9), 0.16488035259264816)]
C14 = [((2, 0.3, 1.7), 0.40508076470064895), ((0.6, 1.4, 0.25), 0.059949560324880865)]
# Unit squares d apart, 3 x 3 rule: relative error against C-11 (mpmath, see above).
NEAR = [(2.0, 1.9302171004016801e-5), (0.3, 0.0060790853305165718)]


def rotation(axis, angle):
    """Rodrigues' rotation matrix."""
    k = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def under(px, py, h):
    """Exact F from (px, py, 0) facing +z to the unit square [0, 1]^2 at height h."""
    return (howell_b3(1 - px, 1 - py, h) - howell_b3(-px, 1 - py, h)
            - howell_b3(1 - px, -py, h) + howell_b3(-px, -py, h))


def check(student_dir, radkit=None):
    lab = load_student(student_dir, "formfactor.py")
    failures = []
    task = guarded(failures, TASK_OF)

    square = np.array([[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]], dtype=float)  # faces down
    R = rotation([1.0, -2.0, 0.5], 1.1)
    for x, what in (((0.3, 0.8, 0.0), "off centre"), ((0.5, 0.5, 0.0), "under the centre")):
        got = task("point_to_polygon", lambda: float(lab.point_to_polygon(
            R @ np.array(x), R @ np.array([0.0, 0.0, 1.0]), square @ R.T)))
        if got is None:
            break
        exact = under(x[0], x[1], 1.0)
        if not math.isclose(got, exact, rel_tol=1e-10):
            failures.append(f"Task 1 (hidden case): point_to_polygon with point, normal and "
                            f"unit square all rotated ({what}) gave {got:.10g}; rotating the "
                            f"whole configuration keeps F = {exact:.10g} (Howell B-3). Use the "
                            "normal you are given, not the z axis.")
            break
    half = under(0.5, 0.5, 1.0) / 2
    for tri in (square[[0, 1, 2]], square[[2, 3, 0]]):
        got = task("point_to_polygon", lambda: float(lab.point_to_polygon(
            np.array([0.5, 0.5, 0.0]), np.array([0.0, 0.0, 1.0]), tri.copy())))
        if got is None:
            break
        if not math.isclose(got, half, rel_tol=1e-10):
            failures.append(f"Task 1 (hidden case): point_to_polygon to a triangle, half of a "
                            f"unit square cut along its diagonal, from under the square's "
                            f"centre gave {got:.10g}; by symmetry it is half the square's B-3 "
                            f"value, {half:.10g}. Loop over all the polygon's vertices.")
            break

    for name, table in (("howell_c11", C11), ("howell_c14", C14)):
        for args, value in table:
            got = task(name, lambda: float(getattr(lab, name)(*map(float, args))))
            if got is None:
                break
            if not math.isclose(got, value, rel_tol=1e-12):
                failures.append(f"Task 4 (hidden case): {name}{args} = {got:.12g}; Howell's "
                                f"closed form gives {value:.12g}.")
                break

    got = task("near_field_errors", lambda: np.asarray(
        lab.near_field_errors([d for d, _ in NEAR], 3), dtype=float))
    exact = np.array([e for _, e in NEAR])
    if got is not None and not (got.shape == exact.shape and np.allclose(got, exact, rtol=1e-6)):
        failures.append(f"Task 5 (hidden case): near_field_errors([2.0, 0.3], n=3) = "
                        f"{np.array2string(got, precision=4)}; the 3 x 3 rule's errors against "
                        f"C-11 are {np.array2string(exact, precision=4)}.")
    return failures
