"""Check for lab 7: GGX Cook-Torrance and normalised Phong written by the student.

Oracles: the normalisation of a microfacet distribution (the projected microfacet area equals the
macro-surface's, integral of D(h) cos(theta_h) = 1); Heitz's weak white furnace (Heitz 2014,
JCGT 3(2), eq. 18: integral of G1(o) max(0, o.h) D(h) dh = cos(theta_o)), which also gives
Lambda = that integral / cos(theta_o) - 1; the normalised Phong lobe's albedo at normal
incidence, ks exactly; and `radkit brdf`'s albedo E(mu) (its own quadrature, docs/shading.md)
against the student's lobe by adaptive quadrature and against the student's Monte Carlo estimate
by a t test (pyradkit.t_test_mean). Each of the six functions is a task of its own.
"""
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
from scipy import integrate

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from pyradkit import guarded, load_student, need_radkit, t_test_mean  # noqa: E402

TASK_OF = {"ggx_D": 1, "smith_lambda": 2, "smith_G1": 3, "phong": 4, "cook_torrance": 5,
           "albedo": 6}
# A t test at 1e-4 rejects a right estimator once in 10 000 checks (|t| > 3.9).
SIGNIFICANCE = 1e-4
# radkit brdf's E against adaptive quadrature (scipy dblquad, 1e-7) of the reference lobe:
# 3.3e-5 apart at (alpha, mu) = (0.3, 0.5), 1e-6 at (0.8, 0.9). The separable G is 3.6e-3 off.
QUADRATURE_TOLERANCE = 2e-4
CASES = ((0.3, 0.5), (0.8, 0.9))


def direction(theta):
    return np.array([math.sin(theta), 0.0, math.cos(theta)])


def radkit_albedo(radkit, alpha, mu, g="height-correlated"):
    out = subprocess.run([radkit, "brdf", "--model", "cook-torrance", "--alpha", str(alpha),
                          "--mu", str(mu), "--g", g], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)["E"]


def visible_area(lab, o, alpha):
    """Integral of max(0, o.h) D(h) dh with the student's D: cos(theta_o) (1 + Lambda(o))."""
    def integrand(theta, phi):
        h = np.array([math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi),
                      math.cos(theta)])
        return max(0.0, float(o @ h)) * float(lab.ggx_D(math.cos(theta), alpha)) * math.sin(theta)
    return integrate.dblquad(integrand, 0, 2 * math.pi, 0, math.pi / 2, epsabs=1e-10)[0]


def check_D(lab, task, failures):
    """Task 1: D is normalised, 2 pi * integral of D(cos) cos sin dtheta = 1, for any alpha."""
    for alpha in (0.1, 0.5, 1.0):
        total = task("ggx_D", lambda: 2 * math.pi * integrate.quad(
            lambda t: float(lab.ggx_D(math.cos(t), alpha)) * math.cos(t) * math.sin(t),
            0, math.pi / 2, epsabs=1e-12, limit=200)[0])
        if total is None:
            return False
        if abs(total - 1) > 1e-6:
            hint = (" (a factor pi: D has 1/pi in front)"
                    if min(abs(total * math.pi - 1), abs(total / math.pi - 1)) < 1e-6 else "")
            failures.append(f"Task 1, ggx_D(alpha = {alpha}) integrates to {total:.6f} over the "
                            f"projected hemisphere, not 1{hint}.")
            return False
    return True


def check_masking(lab, task, failures, d_ok):
    """Tasks 2 and 3 by the weak white furnace (it needs a right D)."""
    if not d_ok:  # until Task 1 passes, only say whether Tasks 2 and 3 are written
        task("smith_lambda", lambda: lab.smith_lambda(0.5, 0.3))
        task("smith_G1", lambda: lab.smith_G1(0.5, 0.3))
        return
    lambda_ok = g1_ok = True
    for alpha in (0.2, 0.6):
        for degrees in (0, 45, 80):
            o = direction(math.radians(degrees))
            visible = visible_area(lab, o, alpha)
            if lambda_ok:
                got = task("smith_lambda", lambda: float(lab.smith_lambda(o[2], alpha)))
                lambda_ok = got is not None
                if got is not None and abs(got - (visible / o[2] - 1)) > 1e-5:
                    failures.append(
                        f"Task 2, smith_lambda({o[2]:.6f}, alpha {alpha}) = {got:.6f} at theta_o "
                        f"{degrees} deg; the weak white furnace needs Lambda = (integral of "
                        f"max(0, o.h) D(h) dh) / cos(theta_o) - 1 = {visible / o[2] - 1:.6f} "
                        "(Heitz 2014, eq. 18). Lambda = (sqrt(1 + alpha^2 tan^2 theta) - 1) / 2: "
                        "tan squared.")
                    lambda_ok = False
            if g1_ok:
                g1 = task("smith_G1", lambda: float(lab.smith_G1(o[2], alpha)))
                g1_ok = g1 is not None
                if g1 is not None and abs(g1 * visible - o[2]) > 1e-5:
                    failures.append(
                        f"Task 3, weak white furnace: G1(o) * integral of max(0, o.h) D(h) dh = "
                        f"{g1 * visible:.6f} at alpha {alpha}, theta_o {degrees} deg, but it must "
                        f"be cos(theta_o) = {o[2]:.6f} (Heitz 2014, eq. 18). G1 = 1 / (1 + "
                        "Lambda).")
                    g1_ok = False


def check_phong(lab, task, failures, ks, n):
    """Task 4: normalised Phong reflects exactly ks at normal incidence (quadrature)."""
    normal = np.array([0.0, 0.0, 1.0])
    total = task("phong", lambda: 2 * math.pi * integrate.quad(
        lambda t: float(lab.phong(normal, direction(t), n, ks)) * math.cos(t) * math.sin(t),
        0, math.pi / 2, epsabs=1e-12, limit=200)[0])
    if total is None:
        return False
    if abs(total - ks) > 1e-7:
        hint = (": that is ks (n + 1) / (n + 2), the normalisation of the lobe without the "
                "cosine of the incident direction; with it, (n + 2) / (2 pi)"
                if abs(total - ks * (n + 1) / (n + 2)) < 1e-6 else "")
        failures.append(f"Task 4, phong(ks = {ks}, n = {n}) reflects {total:.6f} at normal "
                        f"incidence, not ks = {ks}{hint}.")
        return False
    return True


def check_cook_torrance(lab, task, failures, radkit, parts_ok):
    """Task 5: the student's lobe integrated by adaptive quadrature against radkit brdf."""
    for alpha, mu in CASES:
        wo = direction(math.acos(mu))

        def integrand(t, p):
            wi = np.array([math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t)])
            return float(lab.cook_torrance(wo, wi, alpha)) * math.cos(t) * math.sin(t)
        value = task("cook_torrance", lambda: integrate.dblquad(
            integrand, 0, 2 * math.pi, 0, math.pi / 2, epsabs=1e-7)[0])
        if value is None:
            return False
        exact = radkit_albedo(radkit, alpha, mu)
        if abs(value - exact) > QUADRATURE_TOLERANCE:
            separable = radkit_albedo(radkit, alpha, mu, "separable")
            hint = ""
            if abs(value - exact * 4) < 4 * QUADRATURE_TOLERANCE:
                hint = " That is 4 times too much: f = D G F / (4 cos_o cos_i)."
            elif abs(value - separable) < QUADRATURE_TOLERANCE:
                hint = (f" It matches the separable G = G1(o) G1(i) ({separable:.5f}); use the "
                        "height-correlated G2 = 1 / (1 + Lambda(o) + Lambda(i)).")
            if not hint and not parts_ok:
                hint = " It is built on D and Lambda: make Tasks 1 and 2 pass first."
            failures.append(f"Task 5, cook_torrance at alpha {alpha}, mu {mu}: its albedo by "
                            f"quadrature is {value:.5f}, radkit brdf gives {exact:.5f} (within "
                            f"{QUADRATURE_TOLERANCE:g}).{hint}")
            return False
    return True


def t_failure(what, estimate, samples, exact):
    """A failure sentence when the student's (mean, standard error) fails the t test."""
    value, se = map(float, estimate)
    passed, t, p = t_test_mean(value, se, samples - 1, exact, SIGNIFICANCE)
    if passed:
        return None
    if not se > 0:
        return (f"Task 6, albedo of {what}: {value:.5f} with standard error {se:g}; the "
                f"exact value is {exact:.5f}, and a Monte Carlo estimate of a varying integrand "
                "has a positive standard error (the sample standard deviation / sqrt(samples)).")
    return (f"Task 6, albedo of {what}: {value:.5f} +- {se:.2g}, exact {exact:.5f}: t = "
            f"{t:.1f}, p = {p:.1g} < {SIGNIFICANCE:g} (Student's t test, pyradkit.t_test_mean). "
            "Is the estimate the mean of f cos(theta_i) / p(wi), and the error the sample "
            "standard deviation over sqrt(samples)?")


def check(student_dir, radkit_binary=None):
    lab = load_student(student_dir, "brdf.py")
    failures = []
    task = guarded(failures, TASK_OF)
    ks, n = 0.6, 20

    d_ok = check_D(lab, task, failures)
    check_masking(lab, task, failures, d_ok)
    phong_ok = check_phong(lab, task, failures, ks, n)
    try:  # the same advice as every lab, in the repository or in a handout
        need_radkit(radkit_binary, 7)
    except SystemExit as e:
        failures.append(str(e))
        return failures
    parts_ok = not any(f.startswith(("Task 1,", "Task 2,", "not done yet: Task 1",
                                     "not done yet: Task 2")) for f in failures)
    ct_ok = check_cook_torrance(lab, task, failures, radkit_binary, parts_ok)

    # Task 6 on a lobe of the check's own whose albedo is 1 exactly: 3 cos(theta_i) / (2 pi).
    normal = np.array([0.0, 0.0, 1.0])
    samples = 200000
    estimate = task("albedo", lambda: lab.albedo(
        lambda wo, wi: 3 * np.asarray(wi)[..., 2] / (2 * math.pi), normal, samples, 5))
    if estimate is None:
        return failures
    problem = t_failure("f = 3 cos(theta_i) / (2 pi) (exactly 1)", estimate, samples, 1.0)
    if problem:
        failures.append(problem)
        return failures
    # Then on the student's own lobes, where those passed: Phong's ks, radkit's E.
    if phong_ok:
        estimate = task("albedo", lambda: lab.albedo(
            lambda wo, wi: lab.phong(wo, wi, n, ks), normal, samples, 7))
        problem = estimate is not None and t_failure(
            f"the Phong lobe (n = {n}) at normal incidence", estimate, samples, ks)
        if problem:
            failures.append(problem)
    if ct_ok:
        samples = 400000
        for alpha, mu in CASES:
            wo = direction(math.acos(mu))
            estimate = task("albedo", lambda: lab.albedo(
                lambda o, i: lab.cook_torrance(o, i, alpha), wo, samples, 11))
            if estimate is None:
                break
            exact = radkit_albedo(radkit_binary, alpha, mu)
            problem = t_failure(f"Cook-Torrance at alpha {alpha}, mu {mu} (radkit brdf)",
                                estimate, samples, exact)
            if problem:
                failures.append(problem)
                break
            if not failures and alpha == 0.8:
                print(f"lab 7: Cook-Torrance albedo alpha 0.8, mu 0.9: {estimate[0]:.5f} +- "
                      f"{estimate[1]:.1g} (radkit brdf {exact:.5f})")
    return failures
