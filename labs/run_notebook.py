#!/usr/bin/env python3
"""Runs a lab notebook from start to end without Jupyter's interface (nbclient), so a teacher
or the test suite can check that it executes: labs/run_notebook.py NOTEBOOK [--lab-dir DIR]
[--out FILE]. The notebook finds the student's files in --lab-dir (default: its own folder)
and writes the executed copy, with its figures, to --out (default: nothing written).

The notebook reads its scenes from data/ beside labs/ (RADKIT_REPO is set to that folder: the
repository, or a handout's root) and the radkit module from $RADKIT_PYTHON_DIR, else the
repository's build/python, else an installed module."""
import argparse
import os
import sys
from pathlib import Path

sys.dont_write_bytecode = True
LABS = Path(__file__).resolve().parent
REPO = LABS.parent  # the repository, or the root of a handout (labs/make_handout.py)
IN_REPOSITORY = (REPO / "scripts" / "install-deps.sh").is_file()

try:
    import numpy  # noqa: F401  (the notebooks' kernel runs this same Python)
except ImportError:
    sys.exit(f"run_notebook.py: {sys.executable} has no numpy. Fix: run it with the system's "
             "Python, `/usr/bin/python3 labs/run_notebook.py ...`, or install numpy, scipy and "
             "matplotlib for this one")
try:
    import nbformat
    from nbclient import NotebookClient
except ImportError as e:
    how = ("bash scripts/install-deps.sh, or on Debian apt install python3-nbclient "
           "python3-ipykernel" if IN_REPOSITORY else
           "on Debian apt install python3-nbclient python3-ipykernel, elsewhere pip install "
           "nbclient ipykernel")
    sys.exit(f"run_notebook.py needs nbclient, nbformat and ipykernel ({e}). Fix: {how}")

sys.path.insert(0, str(LABS))
from pyradkit import import_radkit  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("notebook")
    parser.add_argument("--lab-dir", help="folder with the student's files")
    parser.add_argument("--out", help="write the executed notebook here")
    args = parser.parse_args()
    path = Path(args.notebook).resolve()
    if not path.is_file():
        sys.exit(f"run_notebook.py: {args.notebook} is not a file. Fix: give a lab's .ipynb, "
                 "e.g. labs/03-write-a-solver/lab3.ipynb")
    lab_dir = Path(args.lab_dir).resolve() if args.lab_dir else path.parent
    if not lab_dir.is_dir():
        sys.exit(f"run_notebook.py: --lab-dir {args.lab_dir} is not a folder. Fix: give the "
                 "folder with your files")
    # Fail here with a message rather than as a traceback inside the kernel.
    number = path.parent.name[:2]
    radkit = import_radkit(int(number) if number.isdigit() else path.name)
    os.environ["LAB_DIR"] = str(lab_dir)
    os.environ["RADKIT_PYTHON_DIR"] = str(Path(radkit.__file__).resolve().parent)
    os.environ["RADKIT_REPO"] = str(REPO)
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # the kernel's debugger notice
    notebook = nbformat.read(path, as_version=4)
    NotebookClient(notebook, timeout=300, kernel_name="python3",
                   resources={"metadata": {"path": str(path.parent)}}).execute()
    if args.out:
        tmp = Path(args.out).with_suffix(".tmp")
        nbformat.write(notebook, tmp)
        tmp.replace(args.out)
    print(f"{path.name}: {len(notebook.cells)} cells executed")


if __name__ == "__main__":
    main()
