"""What the labs' checks share: finding the radkit Python module in the build tree, running the
radkit command line, and importing a student's file from any folder."""
import importlib.util
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


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
