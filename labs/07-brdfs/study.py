"""Lab 7's study, written for you: once brdf.py passes `labs/check 7`, run

    python3 labs/07-brdfs/study.py [--dir DIR] [--radkit PATH] [--out DIR] [--samples N]

to print the albedo tables of README.md and draw albedo.png; hand in its output.
"""
import argparse
import csv
import io
import math
import sys
from pathlib import Path

import numpy as np

sys.dont_write_bytecode = True  # importing the student's file leaves no __pycache__ there
LAB = Path(__file__).resolve().parent
sys.path.insert(0, str(LAB.parent))
from pyradkit import (find_radkit, load_student, need_radkit, run_radkit,  # noqa: E402
                      run_study, save_figure)

ALPHAS = (0.1, 0.3, 0.6, 1.0)


def radkit_table(radkit):
    """{alpha: (mu, E)} from `radkit brdf --table` (its quadrature, height-correlated G)."""
    rows = list(csv.DictReader(io.StringIO(run_radkit(radkit, "brdf", "--table").stdout)))
    out = {}
    for a in ALPHAS:
        sel = [r for r in rows if math.isclose(float(r["alpha"]), a)]
        out[a] = (np.array([float(r["mu"]) for r in sel]), np.array([float(r["E"]) for r in sel]))
    return out


def main():
    parser = argparse.ArgumentParser(description="Lab 7: albedo of Cook-Torrance and Phong")
    parser.add_argument("--dir", default=str(LAB), help="folder with your brdf.py")
    parser.add_argument("--radkit", help="the radkit command (default: build/apps/radkit)")
    parser.add_argument("--out", default=".", help="folder for albedo.png (default: here)")
    parser.add_argument("--samples", type=int, default=200000, help="Monte Carlo samples per mu")
    args = parser.parse_args()
    radkit = need_radkit(find_radkit(args.radkit), 7)
    lab = load_student(args.dir, "brdf.py")
    table = radkit_table(radkit)
    mus = np.arange(0.05, 1.0001, 0.05)

    ct, ph = {}, {}
    for j, a in enumerate(ALPHAS):
        n = 2 / a ** 2 - 2  # the Phong exponent of the same lobe width (Walter et al. 2007)
        wo = [np.array([math.sqrt(1 - m * m), 0, m]) for m in mus]
        ct[a] = np.array([lab.albedo(lambda o, i: lab.cook_torrance(o, i, a), w, args.samples,
                                     100 * j + k) for k, w in enumerate(wo)])
        ph[a] = np.array([lab.albedo(lambda o, i: lab.phong(o, i, n, 1.0), w, args.samples,
                                     50 + 100 * j + k) for k, w in enumerate(wo)])

    print(f"Directional albedo E(mu), yours ({args.samples} cosine-weighted samples) +- one "
          "standard error, against radkit brdf --table (Cook-Torrance, F = 1, height-correlated G) "
          "and normalised Phong (ks = 1, n = 2/alpha^2 - 2)")
    print(f"{'alpha':>5s} {'mu':>5s} {'Cook-Torrance':>20s} {'radkit':>8s} {'z':>6s} "
          f"{'Phong':>18s}")
    worst = 0.0
    for a in ALPHAS:
        rmu, rE = table[a]
        for k, m in enumerate(mus):
            ref = float(np.interp(m, rmu, rE))  # the table has the same mu grid
            (e, se), (p, pse) = ct[a][k], ph[a][k]
            z = (e - ref) / se if se > 0 else float("nan")
            worst = max(worst, abs(z))
            if k % 4 == 3 or k == 0:
                print(f"{a:5.2f} {m:5.2f} {e:12.5f} +- {se:.5f} {ref:8.5f} {z:+6.2f} "
                      f"{p:10.5f} +- {pse:.5f}")
    print(f"largest |z| against radkit over the {len(mus) * len(ALPHAS)} points: {worst:.2f}")
    print("\nenergy single scattering loses at normal incidence, 1 - E(1):")
    for a in ALPHAS:
        print(f"  alpha {a:.1f}: Cook-Torrance {1 - ct[a][-1][0]:.4f} (radkit "
              f"{1 - table[a][1][-1]:.4f}), Phong with n = {2 / a ** 2 - 2:.1f}: "
              f"{1 - ph[a][-1][0]:+.4f}")

    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib is missing: no figure (Debian: python3-matplotlib)")
        return
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for a in ALPHAS:
        line, = left.plot(*table[a], "-", lw=1)
        left.errorbar(mus, ct[a][:, 0], yerr=2 * ct[a][:, 1], fmt="o", ms=3,
                      color=line.get_color(), label=f"alpha = {a}")
        right.errorbar(mus, ph[a][:, 0], yerr=2 * ph[a][:, 1], fmt="o-", ms=3, lw=1,
                       color=line.get_color(), label=f"n = {2 / a ** 2 - 2:.0f}")
    left.set_title("GGX Cook-Torrance, F = 1 (points: yours +- 2 SE; lines: radkit brdf)")
    right.set_title("normalised Phong, ks = 1, n = 2/alpha^2 - 2")
    for ax in (left, right):
        ax.set_xlabel("mu = cos theta_o")
        ax.legend(fontsize=8)
        ax.set_ylim(0, 1.05)
    left.set_ylabel("directional albedo E(mu)")
    save_figure(fig, args.out, "albedo.png", dpi=110)


if __name__ == "__main__":
    run_study(main, 7)
