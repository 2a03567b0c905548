"""Hidden cases for lab 6 (labs/grade.py runs them besides check_lab.py): coloured photons, an
open scene and other total powers. Oracles: radkit's own k-nearest estimate and tally on the same
photons (radkit.photon_map, radkit.photons); the minimum's defining property, no lower error 1 %
either side of optimal_k, with the student's own bias and variance (as the public check).

Catches what the public cases miss: an estimate that assumes every photon carries the first
photon's power (true on lamp.json, where all are the lamp's direct light); a tally that takes N
as the largest path id + 1 instead of the `paths` emitted (the same in the public Cornell box
run, whose last path lands); an optimal_k that ignores total_power (always 1 W in the public
cases)."""
import math

import numpy as np

from pyradkit import LABS, data_file, guarded, import_radkit, load_student

TASK_OF = {"irradiance_estimate": "1", "patch_tally": "2", "knn_bias": "3a",
           "knn_relative_variance": "3b", "optimal_k": "4"}
# (photons, Laplacian, E, total power): the lamp of lamp.json at 4 W/m² (E, its Laplacian and
# the power all four times the 1 W lamp's), and a point of low irradiance with 0.3 W emitted.
OPTIMAL_K_CASES = [(2e4, -4 * 1.0935, 4 * 0.239456, 4.0), (5e5, 0.8, 0.05, 0.3)]


def check_estimate(lab, task, rk, failures):
    mesh = rk.mesh(rk.load_scene(str(data_file("cornell-box.json"))), patches=120)
    pm = rk.photon_map(mesh, photons=20000, seed=7)
    # The floor's photons only: radkit counts photons on surfaces within 25° of the normal, so
    # near the blocks' sides the two would differ for reasons that are not the student's.
    on_floor = np.isin(pm.patch, np.flatnonzero(mesh.surface == 0))
    P, W = pm.positions[on_floor] / 1000, pm.power[on_floor]  # mm -> m, as E is per m²
    rng = np.random.default_rng(66)
    points = np.c_[rng.uniform(100, 450, 30), np.zeros(30), rng.uniform(100, 450, 30)]
    for k in (5, 30, 150):
        got = task("irradiance_estimate", lambda: lab.irradiance_estimate(P, W, points / 1000, k))
        if got is None:
            return
        E, r = (np.asarray(a, dtype=float) for a in got)
        ref = pm.irradiance(points, [0, 1, 0], k=k)
        # Tolerances of the public check: radkit computes distances in float.
        if (E.shape == ref["irradiance"].shape and r.shape == ref["radius"].shape
                and np.allclose(E, ref["irradiance"], rtol=2e-4)
                and np.allclose(r * 1000, ref["radius"], rtol=1e-5)):
            continue
        failures.append(f"Task 1 (hidden case): irradiance_estimate at k = {k} on the Cornell "
                        "box's floor differs from radkit's estimate on the same photons. Its "
                        "photons carry different powers and colours (light from the red and "
                        "green walls): weight each photon's own power, in each channel.")
        return


def check_tally(lab, task, rk, failures):
    mesh = rk.mesh(rk.load_scene(str(LABS / "06-photon-mapping" / "lamp.json")), patches=64)
    N, seed = 5000, 10  # seed 10: the last 3 of the 5000 paths escape and leave no photon
    pm = rk.photon_map(mesh, photons=N, seed=seed)
    tally = rk.photons(mesh, photons=N, seed=seed)  # the same photons, tallied by radkit
    got = task("patch_tally", lambda: lab.patch_tally(pm.patch, pm.path, pm.power, mesh.area, N))
    if got is None:
        return
    H, se = (np.asarray(a, dtype=float) for a in got)
    rho = mesh.reflectance
    ok = rho > 0  # radkit reports the error of B = E + rho H: the black lamp's tells nothing
    expected = np.where(ok, tally["radiosity_error"] / np.where(ok, rho, 1), 0)
    if (H.shape == se.shape == expected.shape and np.allclose(H, tally["irradiance"], rtol=1e-9)
            and np.allclose(se[ok], expected[ok], rtol=1e-6)):
        return
    failures.append(f"Task 2 (hidden case): patch_tally on lamp.json, whose light partly "
                    f"escapes, differs from radkit's tally of the same {N} photons (H and its "
                    f"standard error). Only {len(np.unique(pm.path))} paths left a photon, the "
                    f"last with id {pm.path.max()}; the draws are all N = paths = {N} emitted, "
                    "the others leaving 0 on every patch.")


def check_optimal_k(lab, task, failures):
    for N, lap, E, power in OPTIMAL_K_CASES:
        got = task("optimal_k", lambda: float(lab.optimal_k(N, lap, E, power)))
        if got is None:
            return

        def mse(k):  # the student's own bias and variance, as the public check
            r2 = k * power / (N * math.pi * E)
            bias = task("knn_bias", lambda: float(lab.knn_bias(lap, r2)))
            variance = task("knn_relative_variance", lambda: float(lab.knn_relative_variance(k)))
            return None if bias is None or variance is None else (bias / E) ** 2 + variance
        # k <= 2 fails outright: the variance is infinite there.
        errors = [mse(k) for k in (got, got * 1.01, got / 1.01)] if got > 2 else [1, 0, 0]
        if None in errors:
            return
        if errors[0] > min(errors[1:]):
            failures.append(f"Task 4 (hidden case): optimal_k(N = {N:g}, Laplacian {lap:g}, "
                            f"E {E:g}, total power {power:g} W) = {got:.1f} is not where your "
                            "own bias and variance balance: each photon carries total_power / N, "
                            "so pi r^2 = k total_power / (N E).")
            return


def check(student_dir, radkit=None):
    rk = import_radkit(6)
    lab = load_student(student_dir, "photons.py")
    failures = []
    task = guarded(failures, TASK_OF)
    check_estimate(lab, task, rk, failures)
    check_tally(lab, task, rk, failures)
    check_optimal_k(lab, task, failures)
    return failures
