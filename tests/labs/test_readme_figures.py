#!/usr/bin/env python3
"""The figures in the labs' READMEs ("what a good answer looks like") still come out of the
reference solution: reruns a lab's study on labs/instructor/solutions/ and compares what it
prints with what the README states.

Deterministic figures must agree to the README's printed precision (half a unit of its last
digit). Figures at rounding level (below 1e-12, where the last bits depend on the maths
library) must only stay below 1e-12. Monte Carlo figures must agree within Z standard errors,
estimated from the same runs.

Labs covered, each under a minute: 1 (form factors, deterministic) and 6 (photon mapping, 64
runs per photon count as the README states; the table's bias, spread and radius are Monte
Carlo, its theory columns and optimal_k deterministic).

Usage: test_readme_figures.py --lab N [--radkit PATH] (RADKIT_PYTHON_DIR names the Python
module's folder). Exit status 0 when every figure holds; each drift is printed.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
LABS = REPO / "labs"
Z = 4.0  # standard errors a Monte Carlo figure may move by (two-sided p ~ 6e-5)
ROUNDING = 1e-12


def run_study(lab_folder, radkit, *options):
    """The study's standard output on the reference solution."""
    with tempfile.TemporaryDirectory() as out:
        command = [sys.executable, str(LABS / lab_folder / "study.py"),
                   "--dir", str(LABS / "instructor" / "solutions" / lab_folder), "--out", out,
                   *options]
        if radkit:
            command += ["--radkit", radkit]
        done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} failed:\n{done.stdout}\n{done.stderr}")
    return done.stdout


def half_unit(text):
    """Half a unit of the last printed digit of a number as written (1.98e-1, 0.1998248957)."""
    mantissa, _, exponent = text.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 0.5 * 10.0 ** (-decimals + (int(exponent) if exponent else 0))


def number(text):
    return float(text.replace("−", "-").replace(" ", ""))


def same_printed(readme, now, what, problems):
    """readme (a string as printed there) against now (a float): to printed precision."""
    want = number(readme)
    if abs(want) < ROUNDING and abs(now) < ROUNDING:
        return
    if abs(now - want) > half_unit(readme.replace("−", "-")) * (1 + 1e-9):
        problems.append(f"{what}: README says {readme}, the study now prints {now:.6g}")


def table(readme_text, header):
    """Rows (lists of cell strings) of the Markdown table whose header row starts `header`."""
    start = readme_text.index(header)
    rows = []
    for line in readme_text[start:].splitlines()[2:]:
        if not line.startswith("|"):
            break
        rows.append([c.strip() for c in line.strip("|").split("|")])
    return rows


# --- lab 1 -------------------------------------------------------------------------------------
def lab1(radkit):
    out = run_study("01-form-factors", radkit)
    readme = (LABS / "01-form-factors" / "README.md").read_text()
    problems = []
    printed = {}
    for line in out.splitlines():
        if line.startswith(("C-11", "C-14")):
            printed[line[:28].strip()] = [float(v) for v in line[28:].split()]
    names = {"C-11 unit squares 1 apart": "C-11 unit squares 1 apart",
             "C-11 1 x 1.5 at 0.5": "C-11 1 x 1.5 at 0.5",
             "C-14 W = 1, H = 2, over the floor": "C-14 W = 1, H = 2",
             "C-14 W = 1, H = 2, F21 over the wall": "C-14 F21 over the wall"}
    for row in table(readme, "| case | exact |"):
        now = printed.get(names.get(row[0], row[0]))
        if now is None:
            problems.append(f"lab 1: the README's row '{row[0]}' is not printed by the study")
            continue
        for cell, value, column in zip(row[1:], now, ["exact", 1, 2, 4, 8, 16]):
            same_printed(cell, value, f"lab 1, {row[0]}, n = {column}", problems)

    # The rule's factors against radkit: the README gives the rule's, and says radkit's agree
    # to better than 1e-7.
    mine = {}
    for m in re.finditer(r"(\S+\.json)\s+F\((\w+) -> (\w+)\) = ([\d.]+)\s+radkit ([\d.]+)", out):
        mine[(m[2], m[3])] = (m[4], float(m[4]), float(m[5]))
    paragraph = readme[readme.index("Against radkit formfactors (n = 8)"):]
    paragraph = paragraph[:paragraph.index("\n\n")]
    stated = re.findall(r"0\.\d{10}", paragraph)
    ours = [mine[k][0] for k in (("lower", "upper"), ("floor", "wall"), ("floor", "panel"),
                                 ("panel", "floor"))]
    if stated != ours:
        problems.append(f"lab 1: the README's factors against radkit are {stated}, the study "
                        f"prints {ours}")
    for (i, j), (_, rule, theirs) in mine.items():
        if abs(rule - theirs) >= 1e-7:
            problems.append(f"lab 1: F({i} -> {j}) = {rule:.10f} and radkit's {theirs:.10f} "
                            "differ by 1e-7 or more; the README says better than 1e-7")

    near = {}
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 6 and re.fullmatch(r"\d+\.\d\d", parts[0]):
            near[float(parts[0])] = [float(v) for v in parts[1:]]
    for row in table(readme, "| d | n = 1 |"):
        now = near.get(float(row[0]))
        if now is None:
            problems.append(f"lab 1: d = {row[0]} is not in the study's near-field table")
            continue
        for cell, value, n in zip(row[1:], now, (1, 2, 3, 4, 8)):
            same_printed(cell, value, f"lab 1, near field d = {row[0]}, n = {n}", problems)

    for tol, label in (("0.001", "1e-3"), ("1e-06", "1e-6")):
        m = re.search(rf"below {re.escape(tol)}: (.*)", out)
        now = [int(v) for v in re.findall(r"d = [\d.]+: (\d+)", m[1])] if m else None
        said = re.search(rf"[Bb]elow {re.escape(label)}(?::| they are) ([\d, and]+)", readme)
        want = [int(v) for v in re.findall(r"\d+", said[1])] if said else None
        if now != want:
            problems.append(f"lab 1: points per side below {label}: README {want}, study {now}")
    return problems


# --- lab 6 -------------------------------------------------------------------------------------
def lab6(radkit):
    runs = 64  # the README's figures are for 64 runs per photon count
    out = run_study("06-photon-mapping", None, "--runs", str(runs))
    readme = (LABS / "06-photon-mapping" / "README.md").read_text()
    problems = []
    rows = {}
    for line in out.splitlines():
        p = line.split()
        if len(p) == 10 and p[0].isdigit() and p[1].isdigit():
            rows[(int(p[0]), int(p[1]))] = [float(v) for v in p[2:]]
    for row in table(readme, "| N | k | r (m) |"):
        N, k = int(number(row[0])), int(number(row[1]))
        now = rows.get((N, k))
        what = f"lab 6, N = {N}, k = {k}"
        if now is None:
            problems.append(f"{what}: not printed by the study")
            continue
        r, bias, se, theory_bias, std, theory_std, rms, theory_rms = now
        bias_readme, se_readme = (number(v) for v in row[3].split("±"))
        # Radius: r² of the k-th of a Poisson process is Gamma(k), relative sd 1/sqrt(k), so r's
        # is 1/(2 sqrt(k)) per run; the theory bias goes with the mean r².
        r_se = r / (2 * math.sqrt(k) * math.sqrt(runs))
        if abs(r - number(row[2])) > Z * r_se + half_unit(row[2]):
            problems.append(f"{what}: r {row[2]} in the README, {r:.4f} now (SE {r_se:.1g})")
        if abs(bias - bias_readme) > Z * math.hypot(se, se_readme) + half_unit(row[3].split("±")[0]):
            problems.append(f"{what}: bias {bias_readme:+.4f} ± {se_readme} in the README, "
                            f"{bias:+.4f} ± {se} now")
        tb = number(row[4])
        if abs(theory_bias - tb) > Z * 2 * abs(tb) * r_se / r + half_unit(row[4].replace("−", "-")):
            problems.append(f"{what}: theory bias {row[4]} in the README, {theory_bias:+.4f} now")
        # Sample standard deviation of `runs` estimates: its SE is about std / sqrt(2 (runs - 1)).
        for name, readme_cell, value, extra in (("std", row[5], std, 0.0),
                                                ("RMS", row[7], rms, se)):
            spread = Z * math.hypot(value / math.sqrt(2 * (runs - 1)), extra)
            if abs(value - number(readme_cell)) > spread + half_unit(readme_cell):
                problems.append(f"{what}: {name} {readme_cell} in the README, {value:.4f} now "
                                f"(allowed {spread:.4f})")
        same_printed(row[6], theory_std, f"{what}, theory std", problems)

    printed_k = {int(n): int(k) for n, k in re.findall(r"^\s+(\d+)\s+(\d+)\s+\d+$", out, re.M)}
    for row in table(readme, "| N | optimal_k |"):
        N = int(number(row[0]))
        if printed_k.get(N) != int(number(row[1])):
            problems.append(f"lab 6: optimal_k at N = {N} is {row[1]} in the README, "
                            f"{printed_k.get(N)} now")
    slope = re.search(r"slope of optimal_k against N: ([\d.]+)", out)
    said = re.search(r"slope of `optimal_k` against N is ([\d.]+)", readme)
    if not (slope and said and slope[1] == said[1].rstrip(".")):
        problems.append(f"lab 6: the optimal_k slope: README {said and said[1]}, study "
                        f"{slope and slope[1]}")
    radiosity = re.search(r"largest relative error of the patch means ([\d.e+-]+)", out)
    said = re.search(r"patch means are within ([\d.e+-]+)", readme)
    if not (radiosity and said):
        problems.append("lab 6: the radiosity error of part B is missing from the study or "
                        "the README")
    else:
        same_printed(said[1], float(radiosity[1]), "lab 6, radiosity's patch means", problems)
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lab", type=int, required=True, choices=(1, 6))
    parser.add_argument("--radkit", help="the radkit command (default: the build tree's)")
    args = parser.parse_args()
    problems = {1: lab1, 6: lab6}[args.lab](args.radkit or os.environ.get("RADKIT"))
    for p in problems:
        print(f"  - {p}")
    if problems:
        sys.exit(f"lab {args.lab}: {len(problems)} README figure(s) drifted")
    print(f"lab {args.lab}: the README's figures hold")


if __name__ == "__main__":
    main()
