#!/usr/bin/env python3
"""Grades a folder of hand-ins: labs/grade.py SUBMISSIONS [--labs 1,3] [--out DIR]
[--timeout S] [--memory-mb M] [--radkit PATH] [--no-hidden].

SUBMISSIONS holds one folder per student, each holding one folder per lab handed in, named
like the lab's folder (01-form-factors) or labN (lab1, lab01):

    SUBMISSIONS/ada/01-form-factors/formfactor.py
    SUBMISSIONS/ada/lab3/southwell.py
    SUBMISSIONS/bob/01-form-factors/formfactor.py

For every student and lab, labs/check runs on the student's folder in its own process, with a
time limit and a memory limit, and so does the lab's hidden check when the teachers wrote one
(labs/instructor/hidden/NN-name/hidden_check.py, which defines check(student_dir, radkit) like
a check_lab.py). The tasks of a lab are the "Task k" of its starter files' NotImplementedError
messages. A task earns 1 point when no failure names it ("Task k" in the failure's text) and
no check crashed, ran out of time or of memory. A failure that names no task costs the "other"
point, which is earned only together with at least one task (a blank hand-in earns nothing).

Writes DIR/grades.csv (student, lab, one column per task, other, total, max, status) and
DIR/feedback-STUDENT.txt (each lab's points and its failures, word for word). Status is passed,
failed, timeout, memory, error (the check stopped: a missing file, a student's exception it did
not catch) or missing (no folder for that lab).
"""
import argparse
import csv
import json
import os
import re
import resource
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

LABS = Path(__file__).resolve().parent
HIDDEN = LABS / "instructor" / "hidden"
CRASHES = ("timeout", "memory", "error")
TASK_ID = r"\d+[a-z]?"
TASK_NAMES = re.compile(rf"\bTasks? ({TASK_ID}(?:(?:\s*,\s*|\s+and\s+|\s+or\s+|\s*[-–]\s*)"
                        rf"{TASK_ID})*)\b")


def fail(message):
    sys.exit(f"grade.py: {message}")


def known_labs():
    return {int(p.name[:2]): p for p in sorted(LABS.glob("[0-9][0-9]-*")) if p.is_dir()}


def task_key(task):
    number = re.match(r"\d+", task).group()
    return int(number), task[len(number):]


def lab_tasks(folder):
    """The task ids of a lab, from its starter files' NotImplementedError("Task k: ...")
    messages (else their "Task k" comments), in order."""
    starters = [p for p in sorted(folder.glob("*.py"))
                if p.name not in ("check_lab.py", "study.py")]
    text = "\n".join(p.read_text() for p in starters)
    found = re.findall(r"NotImplementedError\(\s*f?[\"'](Tasks? [^:\"']*)", text)
    if not found:
        found = re.findall(r"(?m)#\s*(Task " + TASK_ID + ")", text)
    tasks = {t for f in found for t in named_ids(f)}
    if not tasks:
        fail(f"{folder.name}: no \"Task k\" in its starter files, so its points cannot be "
             "counted. Fix: mark each unfinished function with "
             "NotImplementedError(\"Task k: ...\")")
    return sorted(tasks, key=task_key)


def named_ids(text):
    """Task ids a text names: "Task 3", "Tasks 1 and 2", "Tasks 2-4", "Task 3a"."""
    ids = []
    for group in TASK_NAMES.findall(text):
        parts = re.split(r"\s*(,|and|or|-|–)\s*", group)
        items, separators = parts[0::2], parts[1::2]
        for i, item in enumerate(items):
            if i and separators[i - 1] in "-–" and items[i - 1].isdigit() and item.isdigit():
                ids += [str(k) for k in range(int(items[i - 1]) + 1, int(item) + 1)]
            else:
                ids.append(item)
    return ids


def tasks_named(failure, tasks):
    """The lab's tasks a failure names; "Task 3" names 3a and 3b when those are the tasks."""
    named = set()
    for t in named_ids(failure):
        if t in tasks:
            named.add(t)
        elif t.isdigit() and any(task_key(k)[0] == int(t) for k in tasks):
            named |= {k for k in tasks if task_key(k)[0] == int(t)}
        elif not t.isdigit() and re.match(r"\d+", t).group() in tasks:
            named.add(re.match(r"\d+", t).group())
    return named


def parse_labs(option, labs):
    if option is None:
        return None
    chosen = []
    for item in option.split(","):
        if not item.strip().isdigit() or int(item) not in labs:
            fail(f"--labs {option}: there is no lab {item.strip()!r}. Fix: give numbers among "
                 f"{', '.join(str(n) for n in labs)}, separated by commas")
        chosen.append(int(item))
    return sorted(set(chosen))


def student_labs(student, labs):
    """{lab number: folder} of one student's hand-in; a folder that names no lab stops it."""
    found = {}
    for path in sorted(student.iterdir()):
        if not path.is_dir() or path.name.startswith((".", "__")):
            continue
        match = re.fullmatch(r"lab0*(\d+)", path.name, re.I)
        number = (int(match.group(1)) if match else
                  int(path.name[:2]) if re.fullmatch(r"\d\d-.+", path.name) else None)
        if number not in labs or (not match and path.name != labs[number].name):
            fail(f"{path}: not a lab folder. Fix: name it like the lab's folder "
                 f"({', '.join(p.name for p in labs.values())}) or labN, or move it out")
        if number in found:
            fail(f"{student.name} has two folders for lab {number}: {found[number].name} and "
                 f"{path.name}. Fix: keep one")
        found[number] = path
    return found


def limits(memory_mb):
    def apply():
        if memory_mb:
            size = memory_mb * 1024 * 1024
            resource.setrlimit(resource.RLIMIT_AS, (size, size))
    return apply


def run_check(lab, folder, check_file, args):
    """(status, failures, message) of labs/check N on folder, with check_file if given."""
    with tempfile.TemporaryDirectory(prefix="radkit-grade-") as tmp:
        report = Path(tmp) / "failures.json"
        command = [sys.executable, str(LABS / "check"), str(lab), "--dir", str(folder.resolve()),
                   "--json", str(report)]
        if check_file:
            command += ["--checks", str(check_file)]
        if args.radkit:
            command += ["--radkit", args.radkit]
        # Its own session, so that a time-out ends radkit runs the check started as well.
        process = subprocess.Popen(command, cwd=tmp, stdout=subprocess.PIPE,
                                   stderr=subprocess.PIPE, text=True, start_new_session=True,
                                   preexec_fn=limits(args.memory_mb))
        try:
            out, err = process.communicate(timeout=args.timeout)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.communicate()
            return "timeout", [], f"stopped after {args.timeout:g} s"
        finally:
            try:
                os.killpg(process.pid, signal.SIGKILL)  # anything it left running
            except ProcessLookupError:
                pass
        if process.returncode in (0, 1) and report.is_file():
            failures = json.loads(report.read_text())["failures"]
            return ("failed" if failures else "passed"), failures, ""
        text = (err or out).strip()
        last = text.splitlines()[-1] if text else f"exit status {process.returncode}"
        if re.search(r"MemoryError|bad_alloc|Cannot allocate memory", text):
            return "memory", [], f"ran out of memory ({args.memory_mb} MB): {last}"
        return "error", [], last


def grade(lab, folder, tasks, args):
    """{task: points, "other": points, "status": ..., "failures": [(source, text)], "notes"}"""
    runs = [("check", None)]
    hidden = args.hidden / folder_name(lab) / "hidden_check.py" if args.hidden else None
    if hidden and hidden.is_file():
        runs.append(("hidden", hidden))
    failures, statuses, notes = [], [], []
    for source, check_file in runs:
        status, found, message = run_check(lab, folder, check_file, args)
        statuses.append(status)
        failures += [(source, f) for f in found]
        if message:
            notes.append(f"{'hidden check' if check_file else 'check'}: {status}: {message}")
    crashed = next((s for s in CRASHES if s in statuses), None)
    named = set()
    unnamed = False
    for _, text in failures:
        these = tasks_named(text, tasks)
        named |= these
        unnamed |= not these
    points = {t: 0 if crashed or t in named else 1 for t in tasks}
    points["other"] = int(not crashed and not unnamed and any(points.values()))
    points["status"] = crashed or ("failed" if failures else "passed")
    points["failures"], points["notes"] = failures, notes
    return points


def folder_name(lab):
    return known_labs()[lab].name


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("submissions", help="the folder with one folder per student")
    parser.add_argument("--labs", help="grade only these labs, e.g. 1,3 (default: every lab "
                        "someone handed in)")
    parser.add_argument("--out", default="grades", help="where grades.csv and the feedback go "
                        "(default: ./grades)")
    parser.add_argument("--timeout", type=float, default=600, help="seconds per check (600)")
    parser.add_argument("--memory-mb", type=int, default=4096,
                        help="address space per check, MB (4096; 0 for no limit)")
    parser.add_argument("--radkit", help="the radkit command the checks run (default as "
                        "labs/check finds it)")
    parser.add_argument("--no-hidden", dest="hidden", action="store_const", const=None,
                        default=HIDDEN, help="skip the hidden checks of labs/instructor/hidden/")
    args = parser.parse_args()

    root = Path(args.submissions)
    if not root.is_dir():
        fail(f"{root} is not a folder. Fix: give the folder that holds one folder per student")
    if args.timeout <= 0 or args.memory_mb < 0:
        fail("--timeout must be above 0 and --memory-mb 0 or more. Fix: e.g. --timeout 600 "
             "--memory-mb 4096")
    labs = known_labs()
    chosen = parse_labs(args.labs, labs)
    students = sorted(p for p in root.iterdir()
                      if p.is_dir() and not p.name.startswith((".", "__")))
    if not students:
        fail(f"{root} holds no student folders. Fix: put each student's lab folders in a folder "
             "of their own, e.g. SUBMISSIONS/ada/01-form-factors/")
    handed = {s.name: student_labs(s, labs) for s in students}
    present = sorted({n for h in handed.values() for n in h})
    chosen = chosen or present
    if not set(chosen) & set(present):
        fail(f"no student in {root} handed in lab {', '.join(map(str, chosen)) or 'any'}. Fix: "
             "name each lab folder like the lab's (01-form-factors) or labN")
    if args.radkit and not Path(args.radkit).is_file():
        fail(f"--radkit {args.radkit} is not a file. Fix: give the radkit program")
    if args.radkit:
        args.radkit = str(Path(args.radkit).resolve())  # the checks run in a temporary folder

    tasks = {n: lab_tasks(labs[n]) for n in chosen}
    columns = sorted({t for n in chosen for t in tasks[n]}, key=task_key)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for student in students:
        feedback = [f"Feedback for {student.name}", ""]
        for n in chosen:
            row = {"student": student.name, "lab": labs[n].name}
            folder = handed[student.name].get(n)
            if folder is None:
                result = {t: 0 for t in tasks[n]}
                result.update(other=0, status="missing", failures=[], notes=[])
            else:
                result = grade(n, folder, tasks[n], args)
            for t in columns:
                row[f"task {t}"] = result[t] if t in tasks[n] else ""
            row["other"] = result["other"]
            row["total"] = sum(result[t] for t in tasks[n]) + result["other"]
            row["max"] = len(tasks[n]) + 1
            row["status"] = result["status"]
            rows.append(row)
            print(f"{student.name:16} {labs[n].name:24} {row['total']:3}/{row['max']:<3} "
                  f"{row['status']}")
            feedback.append(f"lab {n} ({labs[n].name}): {row['total']} of {row['max']} points, "
                            f"{row['status']}")
            feedback.append("  " + ", ".join(f"task {t}: {result[t]}" for t in tasks[n])
                            + f", other: {result['other']}")
            if folder is None:
                feedback.append(f"  no folder {labs[n].name} or lab{n} was handed in")
            feedback += [f"  {note}" for note in result["notes"]]
            feedback += [f"  - {'(hidden case) ' if source == 'hidden' else ''}{text}"
                         for source, text in result["failures"]]
            feedback.append("")
        (out / f"feedback-{student.name}.txt").write_text("\n".join(feedback))
    with open(out / "grades.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, ["student", "lab"] + [f"task {t}" for t in columns]
                                + ["other", "total", "max", "status"])
        writer.writeheader()
        writer.writerows(rows)
    print(f"wrote {out / 'grades.csv'} and {len(students)} feedback files")


if __name__ == "__main__":
    main()
