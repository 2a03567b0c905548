"""Check for lab 7: GGX Cook-Torrance and normalised Phong written by the student.

Oracles: the normalisation of a microfacet distribution (the projected microfacet area equals the
macro-surface's, integral of D(h) cos(theta_h) = 1); Heitz's weak white furnace (Heitz 2014,
JCGT 3(2), eq. 18: integral of G1(o) max(0, o.h) D(h) dh = cos(theta_o)); the normalised Phong
lobe's albedo at normal incidence, ks exactly; and `radkit brdf`'s albedo E(mu) (its own
quadrature, docs/shading.md) against the student's Monte Carlo estimate, within standard errors.
"""
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
from scipy import integrate

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from pyradkit import attempt, load_student  # noqa: E402


def direction(theta):
    return np.array([math.sin(theta), 0.0, math.cos(theta)])


def radkit_albedo(radkit, alpha, mu, g="height-correlated"):
    out = subprocess.run([radkit, "brdf", "--model", "cook-torrance", "--alpha", str(alpha),
                          "--mu", str(mu), "--g", g], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)["E"]


def check(student_dir, radkit_binary=None):
    lab = load_student(student_dir, "brdf.py")
    failures = []

    def task(f):
        return attempt(failures, f)

    # Task 1: D is normalised, 2 pi * integral of D(cos) cos sin dtheta = 1, for any alpha.
    for alpha in (0.1, 0.5, 1.0):
        total = task(lambda: 2 * math.pi * integrate.quad(
            lambda t: float(lab.ggx_D(math.cos(t), alpha)) * math.cos(t) * math.sin(t),
            0, math.pi / 2, epsabs=1e-12, limit=200)[0])
        if total is None:
            break
        if abs(total - 1) > 1e-6:
            hint = (" (a factor pi: D has 1/pi in front)"
                    if min(abs(total * math.pi - 1), abs(total / math.pi - 1)) < 1e-6 else "")
            failures.append(f"ggx_D(alpha = {alpha}) integrates to {total:.6f} over the projected "
                            f"hemisphere, not 1{hint}.")
            break

    # Task 2: Heitz's weak white furnace, G1(o) times the projected area of visible normals.
    if not failures:
        for alpha in (0.2, 0.6):
            for degrees in (0, 45, 80):
                o = direction(math.radians(degrees))

                def integrand(theta, phi):
                    h = np.array([math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi),
                                  math.cos(theta)])
                    return (max(0.0, float(o @ h)) * float(lab.ggx_D(math.cos(theta), alpha))
                            * math.sin(theta))

                value = task(lambda: float(lab.smith_G1(o[2], alpha)) * integrate.dblquad(
                    integrand, 0, 2 * math.pi, 0, math.pi / 2, epsabs=1e-10)[0])
                if value is None:
                    break
                if abs(value - o[2]) > 1e-5:
                    failures.append(
                        f"weak white furnace: G1(o) * integral of max(0, o.h) D(h) dh = {value:.6f} "
                        f"at alpha {alpha}, theta_o {degrees} deg, but it must be cos(theta_o) = "
                        f"{o[2]:.6f} (Heitz 2014, eq. 18). G1 = 1 / (1 + Lambda), Lambda = "
                        "(sqrt(1 + alpha^2 tan^2 theta) - 1) / 2: tan squared.")
                    break

    # Task 3: normalised Phong reflects exactly ks at normal incidence (deterministic quadrature).
    ks, n = 0.6, 20
    normal = np.array([0.0, 0.0, 1.0])
    total = task(lambda: 2 * math.pi * integrate.quad(
        lambda t: float(lab.phong(normal, direction(t), n, ks)) * math.cos(t) * math.sin(t),
        0, math.pi / 2, epsabs=1e-12, limit=200)[0])
    if total is not None and abs(total - ks) > 1e-7:
        hint = (": that is ks (n + 1) / (n + 2), the normalisation of the lobe without the "
                "cosine of the incident direction; with it, (n + 2) / (2 pi)"
                if abs(total - ks * (n + 1) / (n + 2)) < 1e-6 else "")
        failures.append(f"phong(ks = {ks}, n = {n}) reflects {total:.6f} at normal incidence, "
                        f"not ks = {ks}{hint}.")

    # Task 4: the student's Monte Carlo albedo, first where the answer is exact, then of their
    # Cook-Torrance against radkit's quadrature, within 4 of their own standard errors.
    estimate = task(lambda: lab.albedo(lambda wo, wi: lab.phong(wo, wi, n, ks), normal, 200000, 7))
    if estimate is not None:
        value, se = estimate
        if not (se > 0 and abs(value - ks) < 4 * se):
            failures.append(f"albedo of the Phong lobe at normal incidence: {value:.5f} +- "
                            f"{se:.2g}, but it is {ks} exactly (within 4 standard errors).")
    if radkit_binary is None:
        failures.append("the radkit command was not found: build it (bash scripts/build.sh) or "
                        "pass --radkit PATH")
        return failures
    for alpha, mu in ((0.3, 0.5), (0.8, 0.9)):
        wo = direction(math.acos(mu))
        estimate = task(lambda: lab.albedo(lambda o, i: lab.cook_torrance(o, i, alpha), wo,
                                           400000, 11))
        if estimate is None:
            break
        value, se = estimate
        exact = radkit_albedo(radkit_binary, alpha, mu)
        if abs(value - exact) > 4 * se:
            separable = radkit_albedo(radkit_binary, alpha, mu, "separable")
            hint = ""
            if abs(value - exact * 4) < 4 * se * 4:
                hint = " That is 4 times too much: f = D G F / (4 cos_o cos_i)."
            elif abs(value - separable) < 4 * se:
                hint = (f" It matches the separable G = G1(o) G1(i) ({separable:.5f}); use the "
                        "height-correlated G2 = 1 / (1 + Lambda(o) + Lambda(i)).")
            failures.append(f"Cook-Torrance albedo at alpha {alpha}, mu {mu}: yours is "
                            f"{value:.5f} +- {se:.2g}, radkit brdf gives {exact:.5f}.{hint}")
        elif not failures and alpha == 0.8:
            print(f"lab 7: Cook-Torrance albedo alpha 0.8, mu 0.9: {value:.5f} +- {se:.1g} "
                  f"(radkit brdf {exact:.5f})")
    return failures
