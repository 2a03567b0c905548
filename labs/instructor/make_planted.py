#!/usr/bin/env python3
"""Writes planted hand-ins for testing labs/grade.py: labs/instructor/make_planted.py OUT.

OUT gets one folder per planted student, each with lab folders as students hand them in:

    complete/NN-name/    the reference solution of every lab: full points
    starter/NN-name/     the starter files as handed out: no points
    partial/labN/        the solution with one function put back to the starter's version
                         (PARTIAL below): every point but that function's task(s)
    hidden-bug/04-solver-comparison/
                         the solution of lab 4 with a bug only the hidden check finds (ties in
                         best_omega go to the last omega): every point but Task 4

and OUT/expected-grades.csv, the grades labs/grade.py must give them, worked out here from the
starters' NotImplementedError("Task k: ...") messages: a lab's tasks are those of all its
functions, the partial hand-in loses those of the function put back. tests/labs/test_grade.py
runs grade.py on OUT and compares.
"""
import ast
import csv
import re
import sys
from pathlib import Path

INSTRUCTOR = Path(__file__).resolve().parent
LABS = INSTRUCTOR.parent
SOLUTIONS = INSTRUCTOR / "solutions"
# The function each lab's partial hand-in lacks; one whose task no other task's check needs, so
# the points lost are that task's alone (lab 3 has one function for its two tasks).
PARTIAL = {1: "howell_c14", 2: "observed_order", 3: "step", 4: "best_omega",
           5: "reciprocity_error", 6: "optimal_k", 7: "albedo", 8: "power_law"}
HIDDEN_BUG = ("return float(omegas[int(np.argmin(sweeps))])",
              "return float(omegas[len(sweeps) - 1 - int(np.argmin(sweeps[::-1]))])")


def function_lines(source, name):
    """(first, last) 0-based line range of the def of `name` (a method too), decorators in."""
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) and node.name == name:
            first = min([node.lineno] + [d.lineno for d in node.decorator_list]) - 1
            return first, node.end_lineno
    return None


def put_back(solution, starter, name):
    """The solution's source with function `name` replaced by the starter's."""
    theirs, ours = function_lines(starter, name), function_lines(solution, name)
    if theirs is None or ours is None:
        sys.exit(f"make_planted.py: {name} is not in both the starter and the solution. Fix: "
                 "update PARTIAL in make_planted.py")
    lines, given = solution.splitlines(keepends=True), starter.splitlines(keepends=True)
    return "".join(lines[:ours[0]] + given[theirs[0]:theirs[1]] + lines[ours[1]:])


def task_messages(source):
    """{function name: [task ids]} from each function's raise NotImplementedError("Task k ...")."""
    tasks = {}
    for f in ast.walk(ast.parse(source)):
        if not isinstance(f, (ast.FunctionDef, ast.AsyncFunctionDef)):
            continue
        for node in ast.walk(f):
            if (isinstance(node, ast.Call) and getattr(node.func, "id", "") == "NotImplementedError"
                    and node.args and isinstance(node.args[0], ast.Constant)):
                head = re.match(r"Tasks? ([^:]*)", node.args[0].value)
                if head:
                    tasks.setdefault(f.name, []).extend(re.findall(r"\d+[a-z]?", head.group(1)))
    return tasks


def task_order(task):
    number = re.match(r"\d+", task).group()
    return int(number), task[len(number):]


def expected_rows(tasks, lost):
    """grades.csv's rows: {student: {lab: tasks lost or None when missing}}."""
    columns = sorted({t for ts in tasks.values() for t in ts}, key=task_order)
    rows = []
    for student, labs in sorted(lost.items()):
        for lab, own in sorted(tasks.items()):
            missing = lab not in labs
            gone = set(own) if missing else labs[lab]
            row = {"student": student, "lab": lab}
            row.update({f"task {t}": ("" if t not in own else int(t not in gone)) for t in columns})
            row["other"] = int(bool(set(own) - gone))
            row["total"] = len(set(own) - gone) + row["other"]
            row["max"] = len(own) + 1
            row["status"] = "missing" if missing else "passed" if not gone else "failed"
            rows.append(row)
    return ["student", "lab"] + [f"task {t}" for t in columns] + [
        "other", "total", "max", "status"], rows


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_planted.py OUT")
    out = Path(sys.argv[1])
    if out.exists() and any(out.iterdir()):
        sys.exit(f"make_planted.py: {out} exists and is not empty. Fix: give a new folder")
    tasks, lost = {}, {"complete": {}, "starter": {}, "partial": {}, "hidden-bug": {}}
    for folder in sorted(SOLUTIONS.glob("[0-9][0-9]-*")):
        n, lab = int(folder.name[:2]), LABS / folder.name
        messages = {}
        for path in sorted(lab.glob("*.py")):
            if path.name not in ("check_lab.py", "study.py"):
                messages.update(task_messages(path.read_text()))
        tasks[folder.name] = sorted({t for ts in messages.values() for t in ts}, key=task_order)
        lost["complete"][folder.name] = set()
        lost["starter"][folder.name] = set(tasks[folder.name])
        lost["partial"][folder.name] = set(messages.get(PARTIAL[n], []))
        files = sorted(p.name for p in folder.glob("*.py"))
        for student, name in (("complete", folder.name), ("starter", folder.name),
                              ("partial", f"lab{n}")):
            (out / student / name).mkdir(parents=True)
        for file in files:
            solution, starter = (folder / file).read_text(), (lab / file).read_text()
            (out / "complete" / folder.name / file).write_text(solution)
            (out / "starter" / folder.name / file).write_text(starter)
            broken = (put_back(solution, starter, PARTIAL[n])
                      if function_lines(solution, PARTIAL[n]) else solution)
            (out / "partial" / f"lab{n}" / file).write_text(broken)
        if n == 4:
            source = (folder / "analysis.py").read_text()
            if HIDDEN_BUG[0] not in source:
                sys.exit("make_planted.py: lab 4's best_omega changed. Fix: update HIDDEN_BUG")
            (out / "hidden-bug" / folder.name).mkdir(parents=True)
            (out / "hidden-bug" / folder.name / "analysis.py").write_text(
                source.replace(*HIDDEN_BUG))
            lost["hidden-bug"][folder.name] = set(messages["best_omega"])
    header, rows = expected_rows(tasks, lost)
    with open(out / "expected-grades.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, header)
        writer.writeheader()
        writer.writerows(rows)
    print(f"wrote planted hand-ins to {out}")


if __name__ == "__main__":
    main()
