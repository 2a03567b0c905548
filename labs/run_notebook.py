#!/usr/bin/env python3
"""Runs a lab notebook from start to end without Jupyter's interface (nbclient), so a teacher
or the test suite can check that it executes: labs/run_notebook.py NOTEBOOK [--lab-dir DIR]
[--out FILE]. The notebook finds the student's files in --lab-dir (default: its own folder)
and writes the executed copy, with its figures, to --out (default: nothing written)."""
import argparse
import os
import sys
from pathlib import Path

try:
    import nbformat
    from nbclient import NotebookClient
except ImportError as e:
    sys.exit(f"run_notebook.py needs nbclient, nbformat and ipykernel ({e}). "
             "Fix: bash scripts/install-deps.sh (Debian: python3-nbclient python3-ipykernel)")

REPO = Path(__file__).resolve().parent.parent


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("notebook")
    parser.add_argument("--lab-dir", help="folder with the student's files")
    parser.add_argument("--out", help="write the executed notebook here")
    args = parser.parse_args()
    path = Path(args.notebook).resolve()
    os.environ["LAB_DIR"] = str(Path(args.lab_dir).resolve() if args.lab_dir else path.parent)
    os.environ.setdefault("RADKIT_PYTHON_DIR", str(REPO / "build" / "python"))
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
