#!/usr/bin/env python3
"""Writes the labs' student package: labs/make_handout.py OUT.

OUT gets the layout of the repository, cut down to what a student needs:

    OUT/README.md                 what the package is and how to start
    OUT/labs/README.md            labs/README.md without its teachers' sections
    OUT/labs/check, pyradkit.py, run_notebook.py
    OUT/labs/NN-name/             every lab folder: README, starters, check, study, notebook,
                                  figures and the lab's own scenes
    OUT/data/                     the scenes of the repository's data/ that the labs name
    OUT/docs/                     the pages of the repository's docs/ that the labs name, with
                                  their images

Nothing of labs/instructor/ (reference solutions, hidden checks) goes in, nor this script or
grade.py. The package runs outside the repository: labs/check finds radkit from --radkit,
$RADKIT or PATH, and its Python module from $RADKIT_PYTHON_DIR or an installed `import radkit`.

The scenes are found by scanning the lab files for data_file("NAME"), for "data/NAME", and in
notebooks for quoted scene file names; the pages, for "docs/NAME.md". A scene or page named
there but missing stops the script, as does a section of labs/README.md it does not know.
"""
import argparse
import json
import re
import shutil
import sys
from pathlib import Path

LABS = Path(__file__).resolve().parent
REPO = LABS.parent
DATA = REPO / "data"
DOCS = REPO / "docs"
TOOLS = ["check", "pyradkit.py", "run_notebook.py"]
SKIP = {"__pycache__", ".ipynb_checkpoints"}
SCENE = r"[\w.-]+\.(?:json|off|obj|ply|stl)"

# labs/README.md's sections, by heading: which go to students as they are, which not (they are
# about the repository or for teachers), and which a handout rewrites.
KEEP = {"Doing a lab"}
DROP = {"Checking hand-ins", "Adding a lab", "For teachers"}
SETUP = """## Set-up

This package holds `labs/` (the exercises), `data/` (the scenes they use) and `docs/` (the pages
of radkit's documentation they refer to). Run the commands below from the folder that holds
them.

You need radkit's command line and its Python module (your teacher says where they are
installed), and Python 3 with numpy and scipy; the figures also need matplotlib, and running a
notebook without Jupyter needs nbclient and ipykernel.

- The command line: `labs/check` and the studies find `radkit` on your PATH. Otherwise give
  `--radkit /path/to/radkit`, or set `RADKIT=/path/to/radkit` once in your shell.
- The Python module: set `RADKIT_PYTHON_DIR` to the folder that holds it (in a radkit build,
  `build/python`), unless it is installed (`python3 -c "import radkit"` works). Set it before
  you start Jupyter too.

`labs/check` runs with the first `python3` on your PATH. If that one lacks numpy (a virtual
environment, pyenv), run it with the system's: `/usr/bin/python3 labs/check 1`.
"""
TOP_README = """# radkit labs

Exercises on radiosity and global illumination with radkit. Start with `labs/README.md`: it
lists the labs and says how to set up, do and check one (`labs/check N`). `data/` holds the
scenes the labs use, and `docs/` the pages of radkit's documentation they refer to.
"""


def fail(message):
    sys.exit(f"make_handout.py: {message}")


def lab_folders():
    folders = sorted(p for p in LABS.glob("[0-9][0-9]-*") if p.is_dir())
    if not folders:
        fail(f"no lab folders (NN-name) in {LABS}")
    return folders


def lab_files(folder):
    """The files of a lab folder to hand out, without caches and editor or run leftovers."""
    files = []
    for path in sorted(folder.rglob("*")):
        parts = path.relative_to(folder).parts
        if (path.is_file() and not SKIP & set(parts) and not any(p.startswith(".") for p in parts)
                and path.suffix not in (".pyc", ".tmp")):
            files.append(path)
    return files


def notebook_text(path):
    cells = json.loads(path.read_text())["cells"]
    return "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")


def referenced_docs(folders):
    """The pages of docs/ the lab files name, and the images those pages show."""
    named = {}
    for path in [LABS / "README.md"] + [f for d in folders for f in lab_files(d)]:
        if path.suffix in (".py", ".md", ".ipynb"):
            for name in re.findall(r"(?<![\w/.-])docs/([\w-]+\.md)", path.read_text()):
                named.setdefault(name, []).append(str(path.relative_to(REPO)))
    missing = {n: w for n, w in named.items() if not (DOCS / n).is_file()}
    if missing:
        fail("the labs name pages that are not in docs/: " + "; ".join(
            f"{n} (named in {', '.join(sorted(set(w)))})" for n, w in sorted(missing.items()))
            + ". Fix: correct the lab files")
    pages = [DOCS / n for n in sorted(named)]
    images = {DOCS / m for page in pages
              for m in re.findall(r"\]\(([\w./-]+\.(?:png|jpg|jpeg|svg|gif))\)", page.read_text())
              if ".." not in m and (DOCS / m).is_file()}
    return pages + sorted(images)


def referenced_scenes(folders):
    """{scene name in data/: [where it is named]} over every lab file."""
    named = {}
    sources = [LABS / "README.md", LABS / "pyradkit.py"]
    sources += [f for d in folders for f in lab_files(d)]
    for path in sources:
        if path.suffix not in (".py", ".md", ".ipynb", ".json", ".txt") and path.name != "check":
            continue
        text = path.read_text()
        names = set(re.findall(r'data_file\(\s*["\'](' + SCENE + r')["\']', text))
        names |= set(re.findall(r'(?<![\w/.-])data/(' + SCENE + ")", text))
        if path.suffix == ".ipynb":
            # The notebooks open REPO / "data" / name; a quoted scene that is not in the lab's
            # own folder is one of those.
            names |= {n for n in re.findall(r'["\'](' + SCENE + r')["\']', notebook_text(path))
                      if not (path.parent / n).exists()}
        for name in names:
            named.setdefault(name, []).append(str(path.relative_to(REPO)))
    missing = {n: w for n, w in named.items() if not (DATA / n).is_file()}
    if missing:
        fail("the labs name scenes that are not in data/: " + "; ".join(
            f"{n} (named in {', '.join(sorted(set(w)))})" for n, w in sorted(missing.items()))
            + ". Fix: add them to data/ or correct the lab files")
    return named


def scene_dependencies(scene):
    """Files a scene names beside it (a "mesh": "x.off"), found among its JSON strings."""
    if scene.suffix != ".json":
        return []
    found = []

    def walk(value):
        if isinstance(value, dict):
            for v in value.values():
                walk(v)
        elif isinstance(value, list):
            for v in value:
                walk(v)
        elif (isinstance(value, str) and re.fullmatch(r"[\w./-]+\.\w+", value)
              and ".." not in value and (scene.parent / value).is_file()):
            found.append(scene.parent / value)
    walk(json.loads(scene.read_text()))
    return found


def handout_readme():
    """labs/README.md with the repository's set-up replaced and the teachers' sections left out."""
    text = (LABS / "README.md").read_text()
    pieces = re.split(r"(?m)^(?=## )", text)
    out = [pieces[0]]
    for piece in pieces[1:]:
        heading = piece.splitlines()[0][3:].strip()
        if heading == "Set-up":
            out.append(SETUP + "\n")
        elif heading in KEEP:
            out.append(piece)
        elif heading not in DROP:
            fail(f"labs/README.md has a section '## {heading}' that make_handout.py does not "
                 "know. Fix: add it to KEEP (students get it) or DROP in make_handout.py")
    return "".join(out).rstrip() + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", help="the folder to write (new, or empty)")
    args = parser.parse_args()
    out = Path(args.out).resolve()
    if out.exists() and (not out.is_dir() or any(out.iterdir())):
        fail(f"{out} exists and is not an empty folder. Fix: give a new folder")
    if out == LABS or LABS in out.parents:
        fail(f"{out} is inside labs/. Fix: write the handout elsewhere")

    folders = lab_folders()
    scenes = referenced_scenes(folders)
    docs = referenced_docs(folders)
    readme = handout_readme()

    (out / "labs").mkdir(parents=True, exist_ok=True)
    (out / "README.md").write_text(TOP_README)
    (out / "labs" / "README.md").write_text(readme)
    for name in TOOLS:
        shutil.copy2(LABS / name, out / "labs" / name)
    for folder in folders:
        for path in lab_files(folder):
            target = out / "labs" / folder.name / path.relative_to(folder)
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(path, target)
    copied = set()
    queue = [DATA / n for n in sorted(scenes)]
    while queue:
        path = queue.pop(0)
        if path in copied:
            continue
        copied.add(path)
        target = out / "data" / path.relative_to(DATA)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(path, target)
        queue += scene_dependencies(path)
    for path in docs:
        target = out / "docs" / path.relative_to(DOCS)
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(path, target)
    if any(p.name == "instructor" for p in out.rglob("*")):
        fail(f"{out} holds an 'instructor' folder; it must not. Fix: rename the lab file")
    print(f"wrote {out}: {len(folders)} labs, {len(copied)} files in data/ "
          f"({', '.join(sorted(str(p.relative_to(DATA)) for p in copied))}), {len(docs)} in docs/")


if __name__ == "__main__":
    main()
