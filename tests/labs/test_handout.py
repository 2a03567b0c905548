#!/usr/bin/env python3
"""The students' handout (labs/make_handout.py) works outside the repository and gives no
reference code away.

Writes a handout into a temporary folder outside the repository and, there:
1. looks for the reference solutions' code: every function of labs/instructor/solutions/
   that is not given in the starter, its body with docstrings dropped and names renamed in
   order of appearance, searched as a run of statements in every Python file, notebook and
   Markdown code block of the handout; a body that is one expression (a closed form) is also
   searched as any expression;
2. runs every lab's check on the starters as handed out: it must fail with "not done yet"
   lines and no traceback;
3. copies the reference solutions in over the starters: every check must pass;
4. in a copy of labs/ whose check names a scene data/ lacks, make_handout.py must refuse.

Usage: test_handout.py --radkit PATH (RADKIT_PYTHON_DIR names the module's folder). Exit status
0 when all holds; each problem is printed.
"""
import argparse
import ast
import copy
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
LABS = REPO / "labs"
SOLUTIONS = LABS / "instructor" / "solutions"
MIN_NODES = 12  # smaller expressions (a / b, x ** 2) are everyone's, not the solution's


class Rename(ast.NodeTransformer):
    """Renames variables and arguments to v0, v1, ... in order of appearance."""

    def __init__(self):
        self.names = {}

    def _name(self, name):
        return self.names.setdefault(name, f"v{len(self.names)}")

    def visit_Name(self, node):
        return ast.copy_location(ast.Name(id=self._name(node.id), ctx=node.ctx), node)

    def visit_arg(self, node):
        node.arg = self._name(node.arg)
        return node


def canonical(nodes):
    """The text of a statement list or expression with docstrings dropped and names renamed."""
    nodes = [copy.deepcopy(n) for n in (nodes if isinstance(nodes, list) else [nodes])]
    if (nodes and isinstance(nodes[0], ast.Expr) and isinstance(nodes[0].value, ast.Constant)
            and isinstance(nodes[0].value.value, str)):
        nodes = nodes[1:]
    rename = Rename()
    return "\n".join(ast.unparse(rename.visit(n)) for n in nodes)


def size(node):
    """The number of nodes under node (annotate() stores it, for speed)."""
    cached = getattr(node, "_size", None)
    return cached if cached is not None else sum(1 for _ in ast.walk(node))


def annotate(tree):
    for node in reversed(list(ast.walk(tree))):  # children come after their parent in a walk
        node._size = 1 + sum(child._size for child in ast.iter_child_nodes(node))
    return tree


def functions(tree):
    return [n for n in ast.walk(tree) if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))]


def shape(nodes):
    """A cheap fingerprint to compare before the canonical text: node types and size."""
    nodes = nodes if isinstance(nodes, list) else [nodes]
    return tuple((type(n).__name__, size(n)) for n in nodes)


def solution_pieces():
    """[(where, kind, shape, canonical text)] for each solution function not given in the
    starter."""
    pieces = []
    for folder in sorted(SOLUTIONS.glob("[0-9][0-9]-*")):
        for path in sorted(folder.glob("*.py")):
            starter = LABS / folder.name / path.name
            given = set()
            if starter.is_file():
                given = {(f.name, canonical(f.body))
                         for f in functions(ast.parse(starter.read_text()))}
            for f in functions(ast.parse(path.read_text())):
                if (f.name, canonical(f.body)) in given:
                    continue
                where = f"{folder.name}/{path.name}: {f.name}"
                stmts = code(f.body)
                if len(stmts) == 1 and getattr(stmts[0], "value", None) is not None:
                    if size(stmts[0].value) >= MIN_NODES:
                        value = stmts[0].value
                        pieces.append((where, "expression", shape(value), canonical(value)))
                elif sum(size(s) for s in stmts) >= MIN_NODES:
                    pieces.append((where, "statements", shape(stmts), canonical(stmts)))
    return pieces


def code(stmts):
    """The statements without docstrings and other bare constants."""
    return [s for s in stmts if not (isinstance(s, ast.Expr) and isinstance(s.value, ast.Constant))]


def python_sources(root):
    """(path, parsed module) of every piece of Python in the handout."""
    for path in sorted(root.rglob("*")):
        texts = []
        if path.suffix == ".py" or path.name == "check":
            texts = [path.read_text()]
        elif path.suffix == ".ipynb":
            texts = ["".join(c["source"]) for c in json.loads(path.read_text())["cells"]
                     if c["cell_type"] == "code"]
        elif path.suffix == ".md":
            texts = re.findall(r"```(?:python|py)?\n(.*?)```", path.read_text(), re.S)
        for text in texts:
            try:
                yield path, annotate(ast.parse(text))
            except SyntaxError:
                continue


def statement_lists(tree):
    for node in ast.walk(tree):
        for field in ("body", "orelse", "finalbody"):
            value = getattr(node, field, None)
            if isinstance(value, list) and value and isinstance(value[0], ast.stmt):
                yield value


def find_leaks(handout):
    pieces = solution_pieces()
    found = []
    for path, tree in python_sources(handout):
        for where, kind, fingerprint, text in pieces:
            if kind == "expression":
                candidates = (n for n in ast.walk(tree)
                              if isinstance(n, ast.expr) and shape(n) == fingerprint)
            else:
                n = len(fingerprint)
                candidates = (stmts[i:i + n] for stmts in map(code, statement_lists(tree))
                              for i in range(len(stmts) - n + 1)
                              if shape(stmts[i:i + n]) == fingerprint)
            if any(canonical(c) == text for c in candidates):
                found.append(f"{path.relative_to(handout)} holds the body of the reference "
                             f"solution's {where} ({kind})")
    return found, len(pieces)


def run_check(handout, lab, radkit, env):
    start = time.perf_counter()
    done = subprocess.run([sys.executable, str(handout / "labs" / "check"), str(lab),
                           "--radkit", radkit], capture_output=True, text=True, env=env,
                          cwd=handout)
    return done, time.perf_counter() - start


def missing_scene_refused(tmp):
    """make_handout.py, run from a copy of labs/ whose check names a scene not in data/."""
    tree = Path(tmp) / "tree"
    shutil.copytree(LABS, tree / "labs", ignore=shutil.ignore_patterns("instructor", "__pycache__"))
    shutil.copytree(REPO / "data", tree / "data",
                    ignore=shutil.ignore_patterns("*.off", "clouds", "terrain-*", "models"))
    check = next((tree / "labs").glob("05-*")) / "check_lab.py"
    check.write_text(check.read_text() + '\nSCENE = data_file("no-such-scene.json")\n')
    done = subprocess.run([sys.executable, str(tree / "labs" / "make_handout.py"),
                           str(Path(tmp) / "refused")], capture_output=True, text=True)
    if (done.returncode == 0 or "Traceback" in done.stderr
            or "no-such-scene.json (named in labs/05-" not in done.stderr):
        return [f"make_handout.py must refuse a scene missing from data/; it exited "
                f"{done.returncode}:\n{done.stderr.strip()}"]
    return []


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--radkit", required=True)
    args = parser.parse_args()
    radkit = str(Path(args.radkit).resolve())
    if not SOLUTIONS.is_dir():
        sys.exit(f"test_handout.py: {SOLUTIONS} is not here; this test needs the teachers' side")
    problems = []
    with tempfile.TemporaryDirectory(prefix="radkit-handout-") as tmp:
        handout = Path(tmp) / "handout"
        if REPO in handout.parents:
            sys.exit("test_handout.py: the temporary folder is inside the repository. Fix: set "
                     "TMPDIR to a folder outside it")
        subprocess.run([sys.executable, str(LABS / "make_handout.py"), str(handout)], check=True)
        for path in handout.rglob("*"):
            if path.name in ("instructor", "grade.py", "make_handout.py", "solutions", "hidden"):
                problems.append(f"the handout holds {path.relative_to(handout)}")

        leaks, count = find_leaks(handout)
        print(f"searched the handout for {count} reference functions: {len(leaks)} found")
        problems += leaks

        # Only what a student sets: no RADKIT, the module's folder, nothing of the repository.
        env = {k: v for k, v in os.environ.items() if k not in ("RADKIT", "PYTHONPATH")}
        if "RADKIT_PYTHON_DIR" in env:
            env["RADKIT_PYTHON_DIR"] = str(Path(env["RADKIT_PYTHON_DIR"]).resolve())
        labs = sorted(p.name for p in handout.glob("labs/[0-9][0-9]-*"))
        for name in labs:
            lab = int(name[:2])
            done, seconds = run_check(handout, lab, radkit, env)
            out = done.stdout + done.stderr
            print(f"lab {lab} starter: exit {done.returncode}, {seconds:.1f} s")
            if done.returncode != 1 or "not done yet" not in done.stdout or "Traceback" in out:
                problems.append(f"lab {lab} on the starters must fail with 'not done yet' and no "
                                f"traceback; it exited {done.returncode}:\n{out.strip()}")
            for path in (SOLUTIONS / name).iterdir():
                shutil.copy2(path, handout / "labs" / name / path.name)
            done, seconds = run_check(handout, lab, radkit, env)
            print(f"lab {lab} solution: exit {done.returncode}, {seconds:.1f} s")
            if done.returncode != 0 or "all checks passed" not in done.stdout:
                problems.append(f"lab {lab} on the reference solution, in the handout, must "
                                f"pass; it exited {done.returncode}:\n"
                                f"{(done.stdout + done.stderr).strip()}")
        problems += missing_scene_refused(tmp)
    for p in problems:
        print(f"FAIL: {p}")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
