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
    """A scene the labs use: labs/data/NAME in a handout (labs/make_handout.py copies them
    there), else the repository's data/NAME."""
    for folder in (LABS / "data", REPO / "data"):
        if (folder / name).exists():
            return folder / name
    raise SystemExit(f"{name}: not found in {LABS / 'data'} or {REPO / 'data'}. Fix: run the lab "
                     "from the repository or from a complete handout (labs/make_handout.py)")


def import_radkit(lab):
    """The radkit module from the build tree (RADKIT_PYTHON_DIR overrides)."""
    where = os.environ.get("RADKIT_PYTHON_DIR", str(REPO / "build" / "python"))
    if where not in sys.path:
        sys.path.insert(0, where)
    try:
        import radkit
    except ImportError as e:
        raise SystemExit(f"lab {lab} needs the radkit Python module, not found in {where} ({e}). "
                         "Fix: build it with `bash scripts/build.sh`, or set RADKIT_PYTHON_DIR")
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
    """The radkit command a check runs (labs/check found it from --radkit, $RADKIT or the build
    tree), or a stop that says how to get one."""
    if radkit is None or not Path(radkit).is_file():
        raise SystemExit(f"lab {lab} runs the radkit command line, not found (tried --radkit, "
                         "$RADKIT, build/apps/radkit and PATH). Fix: build it with "
                         "`bash scripts/build.sh` from the repository root, or give --radkit PATH")
    return radkit


def run_radkit(radkit, *args):
    """Runs radkit with args (str() of each); stops with its own message when it fails."""
    command = [radkit, *map(str, args)]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed ({done.returncode}):\n{done.stderr.strip()}")
    return done


def find_radkit(option=None):
    """The radkit command: `option` (--radkit), $RADKIT, the build tree, then PATH (None if
    absent). A given --radkit or $RADKIT that is not a file is an error, not a fallback."""
    for given, name in ((option, "--radkit"), (os.environ.get("RADKIT"), "$RADKIT")):
        if given and not Path(given).is_file():
            sys.exit(f"{name} {given} is not a file. Fix: give the radkit binary "
                     "(build it with `bash scripts/build.sh`: build/apps/radkit)")
    for candidate in (option, os.environ.get("RADKIT"), str(REPO / "build" / "apps" / "radkit")):
        if candidate and Path(candidate).is_file():
            return str(Path(candidate).resolve())
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


def slope_mistakes(x, y, sign_reason):
    """(text, value) of the usual wrong log-log slopes of y against x, for which(): linear or
    semi-log axes, swapped axes, the sign lost (sign_reason says why it matters), mixed log
    bases, the end points only."""
    lx, ly = np.log(x), np.log(y)
    exact = float(np.polyfit(lx, ly, 1)[0])
    ends = float((ly[-1] - ly[0]) / (lx[-1] - lx[0]))
    bases = ("the logs have different bases (log10 of one axis, ln of the other): use the same "
             "for both")
    return [
        ("that is the slope on linear axes: a power law is a straight line only on log-log "
         "axes; fit log(y) against log(x)", float(np.polyfit(x, y, 1)[0])),
        ("that is the slope of log(y) against x (semi-log): take the log of x too",
         float(np.polyfit(x, ly, 1)[0])),
        ("that is the slope of y against log(x): take the log of y too",
         float(np.polyfit(lx, y, 1)[0])),
        ("the axes are swapped: fit log(y) against log(x), not log(x) against log(y)",
         float(np.polyfit(ly, lx, 1)[0])),
        (f"the sign is lost: {sign_reason}", -exact),
        (bases, exact * math.log(10)),
        (bases, exact / math.log(10)),
        ("that is the slope through the first and last points only: fit all points by least "
         "squares (numpy.polyfit on the logs)", ends),
    ]


def sentence(text):
    """text as a sentence: capital first letter, full stop."""
    return text[:1].upper() + text[1:] + ("" if text.endswith((".", "?")) else ".")
