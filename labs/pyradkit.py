"""What the labs' checks and studies share: finding the radkit Python module and command line,
running radkit, importing a student's file from any folder, and the closed forms and wording
more than one check uses."""
import csv
import importlib.util
import math
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

LABS = Path(__file__).resolve().parent
REPO = LABS.parent


def data_file(name):
    """A scene the labs use: data/NAME beside labs/, in the repository and in a handout alike
    (labs/make_handout.py copies the scenes the labs name there)."""
    path = REPO / "data" / name
    if not path.is_file():
        raise SystemExit(f"{name}: not found in {REPO / 'data'}. Fix: run the lab from the "
                         "repository or from a complete handout (labs/make_handout.py copies "
                         "the scenes into its data/ folder)")
    return path


def _in_repository():
    """True in a radkit source tree, where building is the fix; a handout has no scripts/."""
    return (REPO / "scripts" / "build.sh").is_file()


def import_radkit(lab):
    """The radkit Python module: from $RADKIT_PYTHON_DIR, else the repository's build tree
    (build/python) when there is one, else an installed `import radkit`."""
    given = os.environ.get("RADKIT_PYTHON_DIR")
    build = REPO / "build" / "python"
    if given and not Path(given).is_dir():
        raise SystemExit(f"RADKIT_PYTHON_DIR={given} is not a folder. Fix: set it to the folder "
                         "that holds radkit's Python module (build/python in a radkit build)")
    where = given or (str(build) if build.is_dir() else None)
    if where and where not in sys.path:
        sys.path.insert(0, where)
    try:
        import radkit
    except ImportError as e:
        tried = f"in {where}" if where else "installed (and RADKIT_PYTHON_DIR is not set)"
        fix = ("build it with `bash scripts/build.sh` from the repository root, or set "
               "RADKIT_PYTHON_DIR to the folder that holds it" if _in_repository() else
               "set RADKIT_PYTHON_DIR to the folder that holds it (build/python in a radkit "
               "build; ask your teacher where radkit is installed), or install the module")
        raise SystemExit(f"lab {lab} needs the radkit Python module, not found {tried} ({e}). "
                         f"Fix: {fix}")
    return radkit


def load_student(student_dir, filename):
    """Imports student_dir/filename as a fresh module (a TA may check many folders in a row)."""
    path = Path(student_dir).resolve() / filename
    if not path.exists():
        raise SystemExit(f"{path}: not found. Fix: give the folder that holds your {filename}")
    spec = importlib.util.spec_from_file_location(f"student_{abs(hash(str(path)))}", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def attempt(failures, f):
    """f(), or None when the student has not written it yet: its NotImplementedError becomes one
    "not done yet" failure (once per task, however many checks call it)."""
    try:
        return f()
    except NotImplementedError as e:
        if f"not done yet: {e}" not in failures:
            failures.append(f"not done yet: {e}")
    return None


def guarded(failures, task_of, passthrough=()):
    """A runner task(label, f) for a check: f(), or None when the student's function is not
    written yet (see attempt) or raised, which becomes a failure naming the task (task_of maps
    the function's name to its number) so the other tasks are still checked. Exceptions in
    passthrough propagate."""
    def task(label, f):
        try:
            return attempt(failures, f)
        except passthrough:
            raise
        except Exception as e:  # a student's bug: report it, keep checking the other tasks
            failures.append(f"Task {task_of[label]}, {label} raised {type(e).__name__}: {e}")
            return None
    return task


def need_radkit(radkit, lab):
    """The radkit command a check runs (labs/check found it from --radkit, $RADKIT, the build
    tree or PATH), or a stop that says how to get one."""
    if radkit is None or not Path(radkit).is_file():
        if _in_repository():
            raise SystemExit(f"lab {lab} runs the radkit command line, not found (tried --radkit, "
                             "$RADKIT, build/apps/radkit and PATH). Fix: build it with "
                             "`bash scripts/build.sh` from the repository root, or give "
                             "--radkit PATH")
        raise SystemExit(f"lab {lab} runs the radkit command line, not found (tried --radkit, "
                         "$RADKIT and PATH). Fix: give --radkit PATH/TO/radkit or set RADKIT to "
                         "it (ask your teacher where radkit is installed), or put its folder on "
                         "PATH")
    return radkit


def run_radkit(radkit, *args):
    """Runs radkit with args (str() of each); stops with its own message when it fails."""
    command = [radkit, *map(str, args)]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed ({done.returncode}):\n{done.stderr.strip()}")
    return done


def find_radkit(option=None):
    """The radkit command: `option` (--radkit), $RADKIT, the repository's build tree when there
    is one, then PATH (None if absent). A given --radkit or $RADKIT that is not a file is an
    error, not a fallback."""
    for given, name in ((option, "--radkit"), (os.environ.get("RADKIT"), "$RADKIT")):
        if given and not Path(given).is_file():
            sys.exit(f"{name} {given} is not a file. Fix: give the radkit program itself "
                     "(build/apps/radkit in a radkit build)")
        if given:
            return str(Path(given).resolve())
    built = REPO / "build" / "apps" / "radkit"
    if built.is_file():
        return str(built.resolve())
    return shutil.which("radkit")


def radkit_surface_factors(radkit, scene):
    """{(from, to): F} from `radkit formfactors` (one patch per surface, default method)."""
    with tempfile.TemporaryDirectory() as tmp:
        run_radkit(radkit, "formfactors", scene, "--patches", 2, "--seed", 1, "--threads", 2,
                   "--out", Path(tmp) / "ff")
        with open(Path(tmp) / "ff" / "surface_formfactors.csv") as f:
            return {(r["from"], r["to"]): float(r["F"]) for r in csv.DictReader(f)}


def howell_b3(a, b, h):
    """Howell B-3: point to a parallel a x b rectangle at height h, one corner above the point.
    Odd in a and in b, so signed corner sums give any rectangle."""
    X, Y = a / h, b / h
    x1, y1 = math.sqrt(1 + X * X), math.sqrt(1 + Y * Y)
    return (X / x1 * math.atan(Y / x1) + Y / y1 * math.atan(X / y1)) / (2 * math.pi)


def slope_hints(exact, linear, semilog, ylogx, swapped, ends, sign_reason):
    """(text, value) of the usual wrong log-log slopes, for which(): each value is what that
    slip gives on the check's data (the check tabulates them); sign_reason says why the sign
    matters there."""
    bases = ("the logs have different bases (log10 of one axis, ln of the other): use the same "
             "for both")
    return [
        ("that is the slope on linear axes: a power law is a straight line only on log-log "
         "axes; fit log(y) against log(x)", linear),
        ("that is the slope of log(y) against x (semi-log): take the log of x too", semilog),
        ("that is the slope of y against log(x): take the log of y too", ylogx),
        ("the axes are swapped: fit log(y) against log(x), not log(x) against log(y)", swapped),
        (f"the sign is lost: {sign_reason}", -exact),
        (bases, exact * math.log(10)),
        (bases, exact / math.log(10)),
        ("that is the slope through the first and last points only: fit all points by least "
         "squares (numpy.polyfit on the logs)", ends),
    ]


def save_figure(fig, folder, name, dpi=110):
    """Lays a study's figure out, writes folder/name and says where."""
    fig.tight_layout()
    path = Path(folder) / name
    fig.savefig(path, dpi=dpi)
    print(f"\nwrote {path}")
    return path


def run_study(main, lab):
    """Runs a study's main(); a task not written yet stops it with a pointer to the check."""
    try:
        main()
    except NotImplementedError as e:
        sys.exit(f"{e} is not done yet; labs/check {lab} says what is missing")


def which(got, variants, rel=1e-7, abs_tol=1e-12):
    """The text of the first (text, value) whose value matches got, else None: how a check
    names the mistake a wrong answer came from."""
    for text, value in variants:
        if value is not None and math.isfinite(value) and \
                math.isclose(got, value, rel_tol=rel, abs_tol=abs_tol):
            return text
    return None


def sentence(text):
    """text as a sentence: capital first letter, full stop."""
    return text[:1].upper() + text[1:] + ("" if text.endswith((".", "?")) else ".")


# --- statistical tests a student can run on a Monte Carlo estimator or a sampler --------------
def t_test(samples, expected, significance=1e-4):
    """Student's t test of the mean of `samples` (independent draws of one estimator) against
    the exact `expected` value, two-sided, in the spirit of Nori's ttest.

    Returns (passed, t, p): t = (mean - expected) / (s / sqrt(n)) with the sample standard
    deviation s, and p the chance of a |t| at least this large when the estimator is unbiased
    (n - 1 degrees of freedom). passed is p >= significance. The default 1e-4 rejects a correct
    estimator once in 10 000 runs, about 3.9 standard errors: a wrong one that shifts the mean
    by a few standard errors fails. With fixed seeds the verdict is repeatable. For an estimate
    already reduced to (mean, standard error), call t_test_mean."""
    x = np.asarray(samples, dtype=float).ravel()
    if len(x) < 2:
        raise ValueError(f"t_test needs at least 2 samples, got {len(x)}")
    return t_test_mean(float(x.mean()), float(x.std(ddof=1) / math.sqrt(len(x))), len(x) - 1,
                       expected, significance)


def t_test_mean(mean, std_error, dof, expected, significance=1e-4):
    """t_test for an estimate given as its mean, its standard error and the degrees of freedom
    of that error (samples - 1 for a plain average). Returns (passed, t, p). A standard error of
    0 passes only when the mean equals `expected` exactly (a zero-variance estimator)."""
    from scipy import stats
    if not std_error > 0:
        same = mean == expected
        return same, (0.0 if same else math.copysign(math.inf, mean - expected)), float(same)
    t = (mean - expected) / std_error
    p = float(2 * stats.t.sf(abs(t), dof))
    return p >= significance, float(t), p


def chi2_test(directions, pdf, bins=(10, 20), significance=0.01, tests=1, min_expected=5.0,
              hemisphere=True, resolution=8):
    """Chi-square goodness-of-fit of sampled directions against their claimed density, in the
    spirit of Mitsuba's chi2 test: is a sampler drawing from the pdf it returns?

    directions: (N, 3) unit vectors the sampler drew (z up), N independent samples;
    pdf(d): density per steradian at (M, 3) unit vectors, vectorised. The (cos theta, phi)
    domain (cos theta in [0, 1] with hemisphere, else [-1, 1]) is cut into bins[0] x bins[1]
    cells of equal solid angle; each cell's expected count is N times the pdf integrated over it
    (a resolution x resolution midpoint rule per cell). Cells expecting fewer than min_expected
    samples are pooled (Mitsuba does the same), and samples below the horizon fall in a cell of
    their own with expected count N (1 - the pdf's integral). Pass tests > 1 when several
    tests run together: the significance is Sidak-corrected, 1 - (1 - significance)^(1/tests).

    Returns (passed, statistic, dof, p): passed is p >= the corrected significance."""
    from scipy import stats
    d = np.asarray(directions, dtype=float)
    n = len(d)
    lo = 0.0 if hemisphere else -1.0
    nt, nphi = bins
    # Observed counts per (cos theta, phi) cell; below-horizon samples counted apart.
    phi = np.mod(np.arctan2(d[:, 1], d[:, 0]), 2 * math.pi)
    inside = d[:, 2] >= lo
    it = np.clip(((d[inside, 2] - lo) / (1 - lo) * nt).astype(int), 0, nt - 1)
    ip = np.clip((phi[inside] / (2 * math.pi) * nphi).astype(int), 0, nphi - 1)
    observed = np.bincount(it * nphi + ip, minlength=nt * nphi).astype(float)
    # Expected counts: the pdf at a resolution x resolution grid of midpoints in each cell.
    k = np.arange(nt * resolution) + 0.5
    mu = lo + (1 - lo) * k / (nt * resolution)
    ph = 2 * math.pi * (np.arange(nphi * resolution) + 0.5) / (nphi * resolution)
    M, P = np.meshgrid(mu, ph, indexing="ij")
    s = np.sqrt(np.maximum(1 - M * M, 0))
    grid = np.stack([s * np.cos(P), s * np.sin(P), M], axis=-1).reshape(-1, 3)
    dens = np.asarray(pdf(grid), dtype=float).reshape(nt, resolution, nphi, resolution)
    cell = (1 - lo) / nt * 2 * math.pi / nphi / resolution ** 2  # solid angle of a sub-cell
    expected = n * dens.sum(axis=(1, 3)).ravel() * cell
    outside = n - expected.sum()
    observed = np.append(observed, np.count_nonzero(~inside))
    expected = np.append(expected, max(outside, 0.0))
    # Pool the cells expecting few samples into one (chi-square needs counts of several).
    small = expected < min_expected
    obs, exp = observed[~small], expected[~small]
    if small.any():
        obs, exp = np.append(obs, observed[small].sum()), np.append(exp, expected[small].sum())
    if np.any((exp == 0) & (obs > 0)):
        return False, math.inf, len(obs) - 1, 0.0  # samples where the pdf says none can be
    keep = exp > 0
    statistic = float(np.sum((obs[keep] - exp[keep]) ** 2 / exp[keep]))
    dof = int(np.count_nonzero(keep)) - 1
    p = float(stats.chi2.sf(statistic, dof))
    corrected = 1 - (1 - significance) ** (1 / tests)
    return p >= corrected, statistic, dof, p
