#!/usr/bin/env python3
"""labs/grade.py: test_grade.py refusals | planted [--radkit PATH].

refusals: bad input stops grade.py with a message that names it and the fix (a missing folder,
an empty one, an unknown lab, a folder that names no lab, two folders for one lab), and a
hand-in that never ends or takes all memory is graded as timeout or memory, not waited for.
Uses only the starter files, so it runs without labs/instructor/.

planted: labs/instructor/make_planted.py writes the planted hand-ins (complete, starter,
partial, hidden-bug) and the grades they must get; grade.py must give exactly those, and its
feedback must carry the failures word for word.
"""
import csv
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
LABS = REPO / "labs"
problems = []


def grade(*args):
    return subprocess.run([sys.executable, str(LABS / "grade.py"), *map(str, args)],
                          capture_output=True, text=True)


def expect_refusal(what, done, *phrases):
    text = done.stdout + done.stderr
    if done.returncode == 0 or "Traceback" in text or not all(p in text for p in phrases):
        problems.append(f"{what}: expected a refusal naming {phrases}, got exit "
                        f"{done.returncode}:\n{text.strip()}")


def copy_starter(target, lab_folder, extra=""):
    target.mkdir(parents=True)
    for path in (LABS / lab_folder).glob("*.py"):
        if path.name not in ("check_lab.py", "study.py"):
            (target / path.name).write_text(path.read_text() + extra)


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def refusals(radkit):
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        out = tmp / "grades"
        expect_refusal("a missing folder", grade(tmp / "nowhere", "--out", out),
                       "nowhere is not a folder", "Fix:")
        (tmp / "empty").mkdir()
        expect_refusal("an empty folder", grade(tmp / "empty", "--out", out),
                       "holds no student folders", "Fix:")
        subs = tmp / "subs"
        copy_starter(subs / "ada" / "05-form-factor-matrix", "05-form-factor-matrix")
        expect_refusal("an unknown lab", grade(subs, "--labs", "5,9", "--out", out),
                       "there is no lab '9'", "Fix:")
        (subs / "bob" / "lab9").mkdir(parents=True)
        expect_refusal("a folder for no lab", grade(subs, "--out", out),
                       "lab9: not a lab folder", "Fix:")
        (subs / "bob" / "lab9").rmdir()
        (subs / "bob" / "lab5").mkdir()
        (subs / "bob" / "05-form-factor-matrix").mkdir()
        expect_refusal("two folders for a lab", grade(subs, "--out", out),
                       "two folders for lab 5", "Fix:")
        for path in ("bob/lab5", "bob/05-form-factor-matrix", "bob"):
            (subs / path).rmdir()

        # A hand-in that loops forever on import, and one that asks for 64 GB.
        copy_starter(subs / "loops" / "lab5", "05-form-factor-matrix", "\nwhile True:\n    pass\n")
        copy_starter(subs / "greedy" / "lab5", "05-form-factor-matrix",
                     "\nhoard = bytearray(64 * 1024 ** 3)\n")
        extra = ["--radkit", radkit] if radkit else []
        done = grade(subs, "--out", out, "--timeout", 5, "--memory-mb", 2048, *extra)
        if done.returncode != 0:
            problems.append(f"grading the time-out and memory cases failed:\n{done.stderr}")
            return
        status = {r["student"]: r["status"] for r in rows(out / "grades.csv")}
        want = {"ada": "failed", "greedy": "memory", "loops": "timeout"}
        if status != want:
            problems.append(f"statuses {status}, expected {want}")
        for r in rows(out / "grades.csv"):
            if r["student"] != "ada" and r["total"] != "0":
                problems.append(f"{r['student']} crashed yet earned {r['total']} points")


def planted(radkit):
    with tempfile.TemporaryDirectory() as tmp:
        subs, out = Path(tmp) / "planted", Path(tmp) / "grades"
        subprocess.run([sys.executable, str(LABS / "instructor" / "make_planted.py"), str(subs)],
                       check=True)
        extra = ["--radkit", radkit] if radkit else []
        done = grade(subs, "--out", out, *extra)
        print(done.stdout, done.stderr)
        if done.returncode != 0:
            problems.append(f"grade.py failed on the planted hand-ins:\n{done.stderr}")
            return
        got, want = rows(out / "grades.csv"), rows(subs / "expected-grades.csv")
        if list(got[0]) != list(want[0]):
            problems.append(f"grades.csv has columns {list(got[0])}, expected {list(want[0])}")
        for g, w in zip(got, want):
            if g != w:
                diff = {k: (g.get(k), w[k]) for k in w if g.get(k) != w[k]}
                problems.append(f"{w['student']}, {w['lab']}: (got, expected) {diff}")
        if len(got) != len(want):
            problems.append(f"{len(got)} rows in grades.csv, expected {len(want)}")
        starter = (out / "feedback-starter.txt").read_text()
        if "  - not done yet: Task 1" not in starter:
            problems.append("feedback-starter.txt lacks the checks' 'not done yet' lines")
        hidden = (out / "feedback-hidden-bug.txt").read_text()
        if "(hidden case) Task 4 (hidden case)" not in hidden:
            problems.append("feedback-hidden-bug.txt lacks the hidden check's failure")


def main():
    if len(sys.argv) < 2 or sys.argv[1] not in ("refusals", "planted"):
        sys.exit("usage: test_grade.py refusals|planted [--radkit PATH]")
    radkit = sys.argv[sys.argv.index("--radkit") + 1] if "--radkit" in sys.argv else None
    (refusals if sys.argv[1] == "refusals" else planted)(radkit)
    for p in problems:
        print(f"FAIL: {p}")
    print(f"{sys.argv[1]}: {'FAILED' if problems else 'all passed'}")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
