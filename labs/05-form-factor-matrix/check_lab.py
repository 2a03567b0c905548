"""Check for lab 5: surface form factors, row deficits and reciprocity read from F.

Oracles: the definitions on a three-patch matrix worked by hand; Howell's catalogue for the unit
cube (C-11, opposite faces: 0.19982489569838746; C-14, adjacent faces: 0.20004377607540316),
closed and with one face open; radkit's report of the reciprocity error of a hemisphere run.
"""
import json
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from pyradkit import data_file, attempt, import_radkit, load_student  # noqa: E402

C11 = 0.19982489569838746
C14 = 0.20004377607540316
# Surface-level accuracy of radkit's default point-polygon F on the cube: the pairs along shared
# edges carry up to 1e-6 each (docs/formfactors.md), measured below 1.5e-6 per face pair.
FACE_TOLERANCE = 2e-6


def check(student_dir, radkit_binary=None):
    rk = import_radkit(5)
    lab = load_student(student_dir, "matrix.py")
    failures = []

    def task(f):
        return attempt(failures, f)

    # Task 1 on a matrix worked by hand: patches 0 and 1 form surface 0 (areas 1 and 3), patch 2
    # is surface 1 (area 2). F_01 = (1 * 0.5 + 3 * 0.2) / 4 = 0.275, F_10 = 2 * 0.55 / 2 = 0.55.
    F = np.array([[0.0, 0.0, 0.5], [0.0, 0.0, 0.2], [0.25, 0.3, 0.0]])
    area, surface = np.array([1.0, 3.0, 2.0]), np.array([0, 0, 1])
    got = task(lambda: np.asarray(lab.surface_factors(F, area, surface), dtype=float))
    exact = np.array([[0.0, 0.275], [0.55, 0.0]])
    if got is not None and not (got.shape == exact.shape and np.allclose(got, exact, rtol=1e-12)):
        mistakes = {
            "the matrix is transposed: row S is the surface the light leaves": exact.T,
            "the rows of a surface's patches are averaged without their areas: F_ST = "
            "sum_i A_i F_iT / A_S, so a large patch counts more": np.array([[0, 0.35], [0.55, 0]]),
            "divided by the area of the receiving surface T; divide by the sender's, A_S":
                np.array([[0, 0.55], [0.275, 0]]),
            "not divided by A_S at all: sum_i A_i F_iT is a flux fraction times area, not a "
            "form factor": np.array([[0, 1.1], [1.1, 0]]),
        }
        hint = next((text for text, wrong in mistakes.items()
                     if got.shape == wrong.shape and np.allclose(got, wrong, rtol=1e-9)),
                    "compare with the definition in README.md")
        failures.append(f"Task 1, surface_factors on the three-patch example gave {got.tolist()}, "
                        f"expected {exact.tolist()}: {hint}.")
        got = None

    # Tasks 1 and 2 on the closed unit cube: opposite faces C-11, adjacent C-14, and every row
    # of F sums to 1 up to F's accuracy.
    cube_file = data_file("cube-one-emitter.json")
    mesh = rk.mesh(rk.load_scene(str(cube_file)), patches=150)
    ff = rk.form_factors(mesh)
    F, area, surface = ff.dense(), mesh.area, mesh.surface
    opposite = {0: 1, 1: 0, 2: 3, 3: 2, 4: 5, 5: 4}  # bottom/top, front/back, left/right
    if got is not None:
        S = np.asarray(lab.surface_factors(F, area, surface), dtype=float)
        exact = np.array([[0.0 if s == t else C11 if opposite[s] == t else C14 for t in range(6)]
                          for s in range(6)])
        worst = np.abs(S - exact).max()
        if worst > FACE_TOLERANCE:
            failures.append(f"Task 1, surface_factors on the closed unit cube is {worst:.3g} "
                            "from Howell's C-11 (opposite faces) and C-14 (adjacent faces).")
    deficit = task(lambda: np.asarray(lab.row_deficit(F), dtype=float))
    d = ff.diagnostics["row_sum"]["max_abs_deviation_from_one"]
    if deficit is not None and np.abs(deficit).max() > d * (1 + 1e-9) + 1e-15:
        failures.append("Task 2, row_deficit on the closed cube should be 0 up to F's accuracy "
                        f"({d:.1e}); it gave up to {np.abs(deficit).max():.3g}.")
        deficit = None

    # Task 2 on the cube without its front face: the light leaving through the opening is the
    # form factor to the missing face, C-11 from the back and C-14 from the other four.
    if deficit is not None:
        scene = json.loads(cube_file.read_text())
        scene["surfaces"] = [s for s in scene["surfaces"] if s["name"] != "front"]
        with tempfile.TemporaryDirectory() as tmp:
            path = Path(tmp) / "open-cube.json"
            path.write_text(json.dumps(scene))
            open_mesh = rk.mesh(rk.load_scene(str(path)), patches=125)
        names = open_mesh.scene.surface_names
        deficit = np.asarray(lab.row_deficit(rk.form_factors(open_mesh).dense()), dtype=float)
        for s, name in enumerate(names):
            on = open_mesh.surface == s
            mean = float(open_mesh.area[on] @ deficit[on] / open_mesh.area[on].sum())
            exact = C11 if name == "back" else C14
            # 1 minus the sum of five surface factors, each within FACE_TOLERANCE.
            if abs(mean - exact) > 5 * FACE_TOLERANCE:
                hint = (" (the sign: the deficit is 1 minus the row sum)"
                        if math.isclose(mean, -exact, rel_tol=1e-3) else "")
                failures.append(f"Task 2, row_deficit on the cube open at the front: the {name} "
                                f"face loses {mean:.6f} of its light, Howell gives "
                                f"{exact:.6f}{hint}.")
                break

    # Task 3: zero where F_ji is set by reciprocity (point-polygon), and radkit's own figures on
    # a hemisphere run, whose rows are estimated independently.
    result = task(lambda: lab.reciprocity_error(F, area))
    if result is not None:
        largest, mean = result
        if largest > 1e-12 or mean > 1e-12:
            failures.append(f"Task 3, reciprocity_error of the point-polygon F is ({largest:.3g}, "
                            f"{mean:.3g}); that F is reciprocal by construction, so both are 0 "
                            "up to rounding. Compare A_i F_ij with A_j F_ji, not F_ij with F_ji.")
        else:
            cornell = rk.mesh(rk.load_scene(str(data_file("cornell-box.json"))), patches=150)
            noisy = rk.form_factors(cornell, method="hemisphere", samples=64, seed=5)
            report = noisy.diagnostics["reciprocity"]
            largest, mean = lab.reciprocity_error(noisy.dense(), cornell.area)
            if not (math.isclose(largest, report["max_relative_error"], rel_tol=1e-9) and
                    math.isclose(mean, report["mean_relative_error"], rel_tol=1e-9)):
                failures.append(
                    f"Task 3, reciprocity_error of a hemisphere run gave ({largest:.6g}, "
                    f"{mean:.6g}); radkit reports ({report['max_relative_error']:.6g}, "
                    f"{report['mean_relative_error']:.6g}). Each unordered pair counts once; "
                    "the relative error divides by the larger of A_i F_ij and A_j F_ji, the mean "
                    "is sum |difference| / sum (A_i F_ij + A_j F_ji).")
            elif not failures:
                print(f"lab 5: hemisphere K = 64 on the Cornell box ({len(cornell)} patches): "
                      f"reciprocity error largest {largest:.3f}, mean {mean:.4f}")
    return failures
