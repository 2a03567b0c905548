"""Hidden cases for lab 7 (labs/grade.py runs them besides check_lab.py): oblique incidence and
other roughness. Oracles: the normalised Phong lobe's property that it peaks, at
ks (n + 2) / (2 pi), in the mirror direction (-x, -y, z) of wo; D's normalisation (integral of
D cos theta_h = 1) at roughness the public check does not use; radkit brdf's albedo E(mu).

Catches what the public cases (Phong only at normal incidence, where wo is its own mirror
direction) miss: a Phong lobe centred on wo instead of its mirror direction."""
import json
import math
import subprocess

import numpy as np
from scipy import integrate

from pyradkit import guarded, load_student, need_radkit

TASK_OF = {"ggx_D": 1, "phong": 4, "cook_torrance": 5}


def direction(theta):
    return np.array([math.sin(theta), 0.0, math.cos(theta)])


def check(student_dir, radkit=None):
    radkit = need_radkit(radkit, 7)
    lab = load_student(student_dir, "brdf.py")
    failures = []
    task = guarded(failures, TASK_OF)

    for alpha in (0.05, 0.3):
        total = task("ggx_D", lambda: 2 * math.pi * integrate.quad(
            lambda t: float(lab.ggx_D(math.cos(t), alpha)) * math.cos(t) * math.sin(t),
            0, math.pi / 2, epsabs=1e-12, limit=400, points=[alpha])[0])
        if total is None:
            break
        if abs(total - 1) > 1e-6:
            failures.append(f"Task 1 (hidden case): ggx_D(alpha = {alpha}) integrates to "
                            f"{total:.6f} over the projected hemisphere, not 1.")
            break

    ks, n, theta = 0.7, 30, math.radians(40)
    wo = direction(theta)
    peak = ks * (n + 2) / (2 * math.pi)
    got = task("phong", lambda: (float(lab.phong(wo, direction(-theta), n, ks)),
                                 float(lab.phong(wo, wo, n, ks))))
    if got is not None and not (math.isclose(got[0], peak, rel_tol=1e-9) and got[1] < 0.01 * peak):
        failures.append(f"Task 4 (hidden case): phong(n = {n}, ks = {ks}) with wo at 40 degrees is "
                        f"{got[0]:.6g} in wo's mirror direction and {got[1]:.6g} back along wo; "
                        f"the lobe peaks at ks (n + 2) / (2 pi) = {peak:.6g} in the mirror "
                        "direction (-x, -y, z) of wo, and is small elsewhere.")

    alpha, mu = 0.5, 0.25
    wo = direction(math.acos(mu))

    def integrand(t, p):
        wi = np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])
        return float(lab.cook_torrance(wo, wi, alpha)) * math.cos(t) * math.sin(t)
    value = task("cook_torrance", lambda: integrate.dblquad(
        integrand, 0, 2 * math.pi, 0, math.pi / 2, epsabs=1e-7)[0])
    if value is not None:
        out = subprocess.run([radkit, "brdf", "--model", "cook-torrance", "--alpha", str(alpha),
                              "--mu", str(mu)], check=True, capture_output=True, text=True)
        exact = json.loads(out.stdout)["E"]
        if abs(value - exact) > 2e-4:  # the public check's tolerance for the same comparison
            failures.append(f"Task 5 (hidden case): cook_torrance at alpha {alpha}, mu {mu} "
                            f"(grazing): its albedo by quadrature is {value:.5f}, radkit brdf "
                            f"gives {exact:.5f}.")
    return failures
