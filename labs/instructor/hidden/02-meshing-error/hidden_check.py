"""Hidden cases for lab 2 (labs/grade.py runs them besides check_lab.py): the same tasks on
other numbers. Oracles: a run folder written here with known values, the point factor
integrated numerically, and exact power laws on which every formula of the lab is exact."""
import csv
import math
import tempfile
from pathlib import Path

from scipy import integrate

from pyradkit import guarded, load_student

TASK_OF = {"surface_radiosity": 1, "point_limit": 2, "loglog_slope": 3, "richardson": 4,
           "observed_order": 5, "extrapolate": 6}
PATCH_COLUMNS = ["id", "surface", "area_m2", "cx_m", "cy_m", "cz_m", "nx", "ny", "nz", "rho_r",
                 "rho_g", "rho_b", "e_r_W_m2", "e_g_W_m2", "e_b_W_m2", "b_r_W_m2", "b_g_W_m2",
                 "b_b_W_m2"]


def write_run(folder):
    """A run folder in radkit's format: 'wall' has unequal patches, 'lamp' brighter patches
    listed first, green and blue differ from red. Returns {surface: (mean, peak)} of red."""
    patches = [("lamp", 0.5, 9.0), ("wall", 0.1, 0.30), ("wall", 0.6, 0.20), ("lamp", 0.5, 7.0),
               ("wall", 0.3, 0.45), ("floor", 1.0, 0.05)]
    with open(folder / "patches.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(PATCH_COLUMNS)
        for i, (surface, area, b) in enumerate(patches):
            w.writerow([i, surface, area, 0, 0, 0, 0, 0, 1, 0.5, 0.5, 0.5, 0, 0, 0,
                        b, 2 * b, 3 * b])
    expected = {}
    with open(folder / "surfaces.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["surface", "area_m2", "b_r_W_m2", "b_g_W_m2", "b_b_W_m2"])
        for surface in ("floor", "wall", "lamp"):
            rows = [(a, b) for s, a, b in patches if s == surface]
            area = sum(a for a, _ in rows)
            mean = sum(a * b for a, b in rows) / area
            w.writerow([surface, area, mean, 2 * mean, 3 * mean])
            expected[surface] = (mean, max(b for _, b in rows))
    return expected


def point_factor(a, b, h):
    """Factor from the floor point under the centre of a parallel a x b rectangle at height h:
    h^2 / (pi (x^2 + y^2 + h^2)^2) integrated over the rectangle."""
    value, _ = integrate.dblquad(lambda y, x: h * h / (math.pi * (x * x + y * y + h * h) ** 2),
                                 -a / 2, a / 2, -b / 2, b / 2, epsabs=1e-13, epsrel=1e-12)
    return value


def close(got, want, rel=1e-9):
    return got is not None and math.isclose(float(got), want, rel_tol=rel, abs_tol=1e-14)


def check(student_dir, radkit=None):
    lab = load_student(student_dir, "meshing.py")
    failures = []
    task = guarded(failures, TASK_OF)

    with tempfile.TemporaryDirectory() as tmp:
        expected = write_run(Path(tmp))
        for surface, (mean, peak) in expected.items():
            got = task("surface_radiosity", lambda: lab.surface_radiosity(tmp, surface))
            if got is None:
                break
            if not (close(got[0], mean, 1e-12) and close(got[1], peak, 1e-12)):
                failures.append(f"Task 1 (hidden case): surface_radiosity of '{surface}' in a run "
                                f"with unequal patches gave {tuple(got)}, not (mean {mean:.6g}, "
                                f"peak {peak:.6g}) of the red channel.")
                break

    for rho, emission, a, b, h in ((0.7, 3.0, 2.0, 0.5, 0.8), (0.25, 10.0, 0.3, 0.3, 2.0)):
        want = rho * emission * point_factor(a, b, h)
        got = task("point_limit", lambda: lab.point_limit(rho, emission, a, b, h))
        if got is not None and not close(got, want, 1e-8):
            failures.append(f"Task 2 (hidden case): point_limit(rho {rho}, E {emission}, a {a}, "
                            f"b {b}, h {h}) = {got}, but the point factor integrated over the "
                            f"rectangle gives {want:.10g}.")

    xs = [2.0, 5.0, 11.0, 40.0]
    got = task("loglog_slope", lambda: lab.loglog_slope(xs, [3.0 * x ** -1.7 for x in xs]))
    if got is not None and not close(got, -1.7):
        failures.append(f"Task 3 (hidden case): loglog_slope of y = 3 x^-1.7 is {got}, not -1.7.")

    # y(s) = L + C s^p is exactly what Richardson and the observed order assume.
    L, C, p, ratio = 2.5, 0.8, 1.5, 3.0
    y = [L + C * (1 / ratio) ** (p * k) for k in range(3)]
    got = task("richardson", lambda: lab.richardson(y[0], y[1], ratio, p))
    if got is not None and not close(got, L):
        failures.append(f"Task 4 (hidden case): richardson({y[0]:.6g}, {y[1]:.6g}, ratio {ratio}, "
                        f"order {p}) = {got}; on y = {L} + {C} s^{p} it must give {L}.")
    got = task("observed_order", lambda: lab.observed_order(y[0], y[1], y[2], ratio))
    if got is not None and not close(got, p):
        failures.append(f"Task 5 (hidden case): observed_order on y = {L} + {C} s^{p} with ratio "
                        f"{ratio} is {got}, not {p}.")

    counts, order = [36, 324, 2916], 2.0  # h = 1/sqrt(N) shrinks by 3 per step
    values = [L + C * (1 / math.sqrt(n)) ** order for n in counts]
    got = task("extrapolate", lambda: lab.extrapolate(counts, values, order))
    if got is not None and not close(got, L):
        failures.append(f"Task 6 (hidden case): extrapolate over {counts} patches with error "
                        f"{C} h^{order} gave {got}, not {L}.")
    return failures
