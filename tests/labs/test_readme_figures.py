#!/usr/bin/env python3
"""The figures in the labs' READMEs ("what a good answer looks like") still come out of the
reference solution: reruns a lab's study on labs/instructor/solutions/ and compares what it
prints with what the README states.

Deterministic figures must agree to the README's printed precision (half a unit of its last
digit). Figures at rounding level (below 1e-12, where the last bits depend on the maths
library) must only stay below 1e-12. Monte Carlo figures must agree within Z standard errors,
estimated from the same runs.

Labs covered, each under a minute: 1 (form factors, deterministic), 2 (meshing error, without
--cornell), 3 (the check's line and the solvers' counts at 151 patches), 4 and 5 (the check's line
and the notebook's printed figures), 6 (photon mapping, 64 runs per photon count as the README
states; the table's bias, spread and radius are Monte Carlo, its theory columns and optimal_k
deterministic), 7 (BRDF albedos: Monte Carlo losses within Z standard errors, radkit's quadrature
to printed precision) and 8 (hierarchy, without the seconds columns).

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


def run_check(n, radkit):
    """The `lab N: ...` line that `labs/check N --solution` prints."""
    command = [sys.executable, str(LABS / "check"), str(n), "--solution"]
    if radkit:
        command += ["--radkit", radkit]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} failed:\n{done.stdout}\n{done.stderr}")
    return next(l for l in done.stdout.splitlines() if l.startswith(f"lab {n}: "))


NUMBER = r"[-+−]?\d[\d.]*(?:e[-+]?\d+)?"


def same_line(readme, line, what, problems, monte_carlo=None):
    """The check's printed line against the README's quotation of it (in backquotes, maybe
    wrapped, maybe only its end): the same words, and each number to its printed precision,
    except the numbers at the positions (counted in the quotation) in monte_carlo, {index:
    index of its standard error}, which must agree within Z standard errors."""
    monte_carlo = monte_carlo or {}
    template = re.sub(NUMBER, "#", line)
    quotes = [" ".join(q.split()) for q in re.findall(r"`([^`]*)`", readme)]
    quotes = [q for q in quotes if re.search(r"\d", q) and len(q) > 20
              and template.endswith(re.sub(NUMBER, "#", q))]
    if not quotes:
        problems.append(f"{what}: the README does not quote the check's line `{line}`")
        return
    said = max(quotes, key=len)
    a = re.findall(NUMBER, said)
    b = re.findall(NUMBER, line)[-len(a):]
    for k, (x, y) in enumerate(zip(a, b)):
        if k in monte_carlo:
            se = number(b[monte_carlo[k]])
            if abs(number(x) - number(y)) > Z * math.sqrt(2) * se + half_unit(x):
                problems.append(f"{what}: {x} in the README, {y} now (SE {se})")
        elif k not in monte_carlo.values():
            same_printed(x, number(y), f"{what}, figure {k + 1} of `{said}`", problems)


def cell(text):
    return text.replace(" ", "")


# --- lab 2 -------------------------------------------------------------------------------------
def lab2(radkit):
    out = run_study("02-meshing-error", radkit)
    readme = (LABS / "02-meshing-error" / "README.md").read_text()
    problems = []
    same_line(readme, run_check(2, radkit), "lab 2, the check", problems)
    blocks = out.split("\nB. ")
    a = {int(p[0]): p[1:] for p in (l.split() for l in blocks[0].splitlines())
         if len(p) == 8 and p[0].isdigit()}
    for row in table(readme, "| patches | h | mean | peak |"):
        now = a.get(int(row[0]))
        if now is None:
            problems.append(f"lab 2, A: {row[0]} patches not printed")
            continue
        for col, k in ((2, 1), (3, 2), (4, 3), (5, 4), (6, 5), (7, 6)):
            if row[col]:
                same_printed(cell(row[col]), float(now[k]), f"lab 2, A, {row[0]} patches, column {col + 1}",
                             problems)
    m = re.search(r"against log\(patches\): (\S+); against log\(h\): (\S+)", blocks[0])
    said = re.search(r"slope (\S+) against N and (\S+) against h", readme)
    same_printed(said[1], float(m[1]), "lab 2, A, slope against N", problems)
    same_printed(said[2], float(m[2]), "lab 2, A, slope against h", problems)
    b = {}
    for k, block in enumerate(blocks[1:]):
        for p in (l.split() for l in block.splitlines()):
            if len(p) == 4 and p[0].isdigit():
                b.setdefault(int(p[0]), [None] * 6)[3 * k:3 * k + 3] = [float(v) for v in p[1:]]
    for row in table(readme, "| patches | reflective-squares |"):
        now = b[int(row[0])]
        for col in range(1, 7):
            if row[col]:
                same_printed(cell(row[col]), now[col - 1], f"lab 2, B, {row[0]} patches, column {col + 1}",
                             problems)
    fits = re.findall(r"against log\(patches\): (\S+); extrapolated with order 2: (\S+), with the "
                      r"observed order (\S+): (\S+)", "\n".join(blocks[1:]))
    said = re.search(r"slopes of the changes against N are (\S+) for the parallel squares and "
                     r"(\S+) for the", readme)
    for k in range(2):
        same_printed(said[k + 1], float(fits[k][0]), f"lab 2, B, slope {k + 1}", problems)
    said = re.search(r"extrapolation is (\S+) with order 2 and (\S+) with the", readme)
    same_printed(said[1], float(fits[0][1]), "lab 2, B, squares, order 2", problems)
    same_printed(said[2], float(fits[0][3]), "lab 2, B, squares, observed order", problems)
    said = re.search(r"Corner: (\S+) with order 2 and (\S+) with the observed (\S+)\.", readme)
    for k, v in ((1, fits[1][1]), (2, fits[1][3]), (3, fits[1][2])):
        same_printed(said[k], float(v), f"lab 2, B, corner, figure {k}", problems)
    return problems


# --- lab 3 -------------------------------------------------------------------------------------
def lab3(radkit):
    readme = (LABS / "03-write-a-solver" / "README.md").read_text()
    problems = []
    same_line(readme, run_check(3, radkit), "lab 3, the check", problems)
    sys.path[:0] = [str(REPO / "build" / "python")] if not os.environ.get("RADKIT_PYTHON_DIR") \
        else [os.environ["RADKIT_PYTHON_DIR"]]
    import radkit as rk
    mesh = rk.mesh(rk.load_scene(str(REPO / "data" / "cornell-box.json")), patches=150)
    system = rk.System(rk.form_factors(mesh))
    runs = {n: rk.solve(system, n, tolerance=1e-6) for n in ("gauss-seidel", "jacobi", "southwell")}
    said = re.search(r"Gauss-Seidel\s+needs (\d+) sweeps and Jacobi (\d+) to the same tolerance, "
                     r"and the built-in `southwell` ([\d ]+) shots\s+\(([\d.]+) sweeps\)", readme)
    if not said:
        return problems + ["lab 3: the README's solver counts are missing"]
    for name, k in (("gauss-seidel", 1), ("jacobi", 2), ("southwell", 3)):
        if runs[name]["iterations"] != int(cell(said[k])):
            problems.append(f"lab 3: {name} {said[k]} in the README, {runs[name]['iterations']} now")
    same_printed(said[4], runs["southwell"]["history"]["sweeps"][-1], "lab 3, southwell's sweeps",
                 problems)
    return problems


def run_notebook(folder, notebook):
    """The text outputs of a lab notebook run on the reference solution."""
    with tempfile.TemporaryDirectory() as tmp:
        command = [sys.executable, str(LABS / "run_notebook.py"), str(LABS / folder / notebook),
                   "--lab-dir", str(LABS / "instructor" / "solutions" / folder),
                   "--out", str(Path(tmp) / notebook)]
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            sys.exit(f"{' '.join(command)} failed:\n{done.stdout}\n{done.stderr}")
        import json
        cells = json.loads((Path(tmp) / notebook).read_text())["cells"]
    return "".join("".join(o.get("text", "")) for c in cells for o in c.get("outputs", []))


# --- lab 4 -------------------------------------------------------------------------------------
def lab4(radkit):
    readme = " ".join((LABS / "04-solver-comparison" / "README.md").read_text().split())
    problems = []
    same_line(readme, run_check(4, radkit), "lab 4, the check", problems)
    out = run_notebook("04-solver-comparison", "lab4.ipynb")
    now = {p[0]: p[1:] for p in (l.split() for l in out.splitlines()) if len(p) == 5}
    said = re.search(r"Jacobi (\d+) sweeps \(factor ([\d.]+) over them; spectral radius ([\d.]+)\), "
                     r"Gauss-Seidel (\d+), SOR with its default ω (\d+),", readme)
    radius = float(re.search(r"spectral radius of rho F: (\S+)", out)[1])
    for what, want, value in (("Jacobi sweeps", said[1], now["jacobi"][1]),
                              ("Jacobi factor", said[2], now["jacobi"][3]),
                              ("spectral radius", said[3], radius),
                              ("Gauss-Seidel sweeps", said[4], now["gauss-seidel"][1]),
                              ("SOR sweeps", said[5], now["sor"][1])):
        same_printed(want, float(value), f"lab 4, {what}", problems)
    said = re.search(r"Progressive refinement needs ([\d.]+) sweeps \(([\d ]+) shots\)", readme)
    same_printed(said[1], float(now["southwell"][1]), "lab 4, southwell's sweeps", problems)
    if int(cell(said[2])) != int(now["southwell"][0]):
        problems.append(f"lab 4: southwell's shots {said[2]} in the README, {now['southwell'][0]} now")
    best = re.search(r"best omega on the room: (\S+)", out)[1]
    said = re.search(r"finds (\d+) sweeps for ω from ([\d.]+) to", readme)
    if float(best) != float(said[2]):
        problems.append(f"lab 4: the best ω {said[2]} in the README, {best} now")
    return problems


# --- lab 5 -------------------------------------------------------------------------------------
def lab5(radkit):
    readme = " ".join((LABS / "05-form-factor-matrix" / "README.md").read_text().split())
    problems = []
    # The reciprocity figures come from a hemisphere run (ray casting): its mean is left out.
    line = run_check(5, radkit)
    said = re.search(r"reciprocity error largest ([\d.]+)", readme)
    now = re.search(r"reciprocity error largest ([\d.]+)", line)
    same_printed(said[1], float(now[1]), "lab 5, the largest reciprocity error", problems)
    out = run_notebook("05-form-factor-matrix", "lab5.ipynb")
    deficit = dict(re.findall(r"^(\w[\w ]*?)\s+leaves the box: (\S+)", out, re.M))
    said = re.search(r"deficit of ([\d.]+) for the floor and ([\d.]+) for the back wall", readme)
    same_printed(said[1], float(deficit["floor"]), "lab 5, the floor's deficit", problems)
    same_printed(said[2], float(deficit["back wall"]), "lab 5, the back wall's deficit", problems)
    return problems


# --- lab 7 -------------------------------------------------------------------------------------
def lab7(radkit):
    out = run_study("07-brdfs", radkit)  # 200 000 samples per point, as the README states
    readme = " ".join((LABS / "07-brdfs" / "README.md").read_text().split())
    problems = []
    same_line(readme, run_check(7, radkit), "lab 7, the check", problems, monte_carlo={2: 3})
    # At mu = 1 the table prints each estimate and its standard error.
    se = {float(p[0]): float(p[4]) for p in (l.split() for l in out.splitlines())
          if len(p) == 10 and p[1] == "1.00"}
    loss = re.findall(r"alpha (\S+): Cook-Torrance (\S+) \(radkit (\S+)\), Phong with n = \S+: (\S+)",
                      out)
    said = re.search(r"Cook-Torrance loses ([\d.]+), ([\d.]+), ([\d.]+) and ([\d.]+) for α = 0.1, "
                     r"0.3, 0.6 and 1 \(radkit: ([\d.]+), ([\d.]+), ([\d.]+), ([\d.]+)\), while Phong's "
                     r"loss is within ±([\d.]+) of zero", readme)
    for k, (a, ct, rk, phong) in enumerate(loss):
        ours, theirs = said[k + 1], said[k + 5]
        if abs(number(ours) - float(ct)) > Z * math.sqrt(2) * se[float(a)] + half_unit(ours):
            problems.append(f"lab 7: Cook-Torrance's loss at alpha {a}: {ours} in the README, {ct} "
                            f"now (SE {se[float(a)]})")
        same_printed(theirs, float(rk), f"lab 7, radkit's loss at alpha {a}", problems)
        if abs(float(phong)) > float(said[9]):
            problems.append(f"lab 7: Phong's loss at alpha {a} is {phong}, the README says within "
                            f"±{said[9]}")
    # Every z-score is a Monte Carlo estimate against radkit's quadrature: the README's largest
    # |z| must still hold as an upper bound on a sample of 80 (each within Z standard errors).
    worst = float(re.search(r"largest \|z\| against radkit over the \d+ points: (\S+)", out)[1])
    if worst > Z:
        problems.append(f"lab 7: the largest |z| against radkit is {worst}, above {Z}")
    return problems


# --- lab 8 -------------------------------------------------------------------------------------
def lab8(radkit):
    out = run_study("08-hierarchy", radkit)
    readme = (LABS / "08-hierarchy" / "README.md").read_text()
    flat = " ".join(readme.split())
    problems = []
    same_line(flat, run_check(8, radkit), "lab 8, the check", problems)
    parts = out.split("\nB. ")
    b_part, c_part = parts[1].split("\nC. ")
    for part, header, width, columns in (
            (parts[0], "| ε | links | floor leaves | lamp leaves |", 10, range(1, 9)),
            (b_part, "| ε | links | floor leaves | mean − ρ E C-11 |", 6, range(1, 5)),
            (c_part, "| ε | leaves N | links | N² |", 7, range(1, 6))):
        rows = {float(p[0]): p for p in (l.split() for l in part.splitlines())
                if len(p) in (width, width - 1) and re.fullmatch(r"\de-0\d", p[0])}
        for row in table(readme, header):  # the last column, seconds, is not compared
            now = rows.get(float(row[0]))
            if now is None:
                problems.append(f"lab 8: ε = {row[0]} of the table '{header}' is not printed")
                continue
            for col in columns:
                if row[col]:
                    same_printed(cell(row[col]), number(now[col]),
                                 f"lab 8, {header[:30]}…, ε = {row[0]}, column {col + 1}", problems)
    fits = re.findall(r"(\d[\d.]*) eps\^(\S+?)[;\n ]", out + "\n")
    said = re.findall(r"(\d[\d.]*) ε\^(−?\d+(?:\.\d+)?)",
                      " ".join(readme.split("## What a good answer looks like")[1].split()))
    if len(fits) < 6 or len(said) < 6:
        problems.append(f"lab 8: fits printed {fits}, README {said}")
    else:
        for (c, p), (cs, ps) in zip(fits[:6], said[:6]):
            same_printed(cs, float(c), "lab 8, a fit's prefactor", problems)
            same_printed(ps, float(p), "lab 8, a fit's exponent", problems)
    m = re.search(r"L1 error against links: (\S+) links\^(\S+)", out)
    s = re.search(r"L1 error (\S+) links\^(−?[\d.]+)\.", readme)
    same_printed(s[1], float(m[1]), "lab 8, L1 against links, prefactor", problems)
    same_printed(s[2], float(m[2]), "lab 8, L1 against links, exponent", problems)
    m = re.search(r"links (\S+) leaves\^(\S+)", out)
    s = re.search(r"links (\S+) N\^(\S+)\.", readme)
    same_printed(s[1], float(m[1]), "lab 8, Cornell links against N, prefactor", problems)
    same_printed(s[2], float(m[2]), "lab 8, Cornell links against N, exponent", problems)
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--lab", type=int, required=True, choices=(1, 2, 3, 4, 5, 6, 7, 8))
    parser.add_argument("--radkit", help="the radkit command (default: the build tree's)")
    args = parser.parse_args()
    problems = {1: lab1, 2: lab2, 3: lab3, 4: lab4, 5: lab5, 6: lab6, 7: lab7,
                8: lab8}[args.lab](args.radkit or os.environ.get("RADKIT"))
    for p in problems:
        print(f"  - {p}")
    if problems:
        sys.exit(f"lab {args.lab}: {len(problems)} README figure(s) drifted")
    print(f"lab {args.lab}: the README's figures hold")


if __name__ == "__main__":
    main()
