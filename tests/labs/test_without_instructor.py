#!/usr/bin/env python3
"""The labs in a course's copy of the repository that deleted labs/instructor/ (its README,
"Deleting it"): test_without_instructor.py [--radkit PATH].

Copies the repository's files (tracked and new, as git lists them, so that uncommitted edits
count) without labs/instructor/ into a temporary folder, with no build tree, and there:
- `labs/check N` on every lab's starters fails with "not done yet" lines only, no traceback;
- `labs/check N --solution` refuses, saying the solutions are not in this copy;
- `labs/grade.py` grades a student who handed in every starter: it runs without the hidden
  checks (they are optional), gives 0 points, and refuses bad input as it documents.
radkit's command line comes from --radkit (default: this repository's build/apps/radkit), its
Python module from $RADKIT_PYTHON_DIR, as a course's copy would be told.
"""
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
problems = []


def copy_without_instructor(target):
    listed = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                            cwd=REPO, capture_output=True, text=True, check=True).stdout
    for name in filter(None, listed.split("\0")):
        if name.startswith("labs/instructor/") or not (REPO / name).is_file():
            continue  # a deleted file still listed, or the teachers' side
        (target / name).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(REPO / name, target / name)


def run(copy, *args):
    done = subprocess.run([sys.executable, *map(str, args)], cwd=copy, capture_output=True,
                          text=True, timeout=300)
    return done, done.stdout + done.stderr


def main():
    radkit = (sys.argv[sys.argv.index("--radkit") + 1] if "--radkit" in sys.argv
              else str(REPO / "build" / "apps" / "radkit"))
    if not Path(radkit).is_file():
        sys.exit(f"test_without_instructor.py: no radkit at {radkit}. Fix: build it or give "
                 "--radkit PATH")
    with tempfile.TemporaryDirectory(prefix="radkit-no-instructor-") as tmp:
        copy = Path(tmp) / "radkit"
        copy_without_instructor(copy)
        if (copy / "labs" / "instructor").exists() or not (copy / "labs" / "check").is_file():
            sys.exit("test_without_instructor.py: the copy is not a copy without labs/instructor/")
        labs = sorted(p for p in (copy / "labs").glob("[0-9][0-9]-*") if p.is_dir())
        if len(labs) < 8:
            problems.append(f"the copy holds {len(labs)} lab folders, expected 8 or more")
        for lab in labs:
            n = int(lab.name[:2])
            done, text = run(copy, "labs/check", n, "--radkit", radkit)
            items = [line for line in done.stdout.splitlines() if line.startswith("  - ")]
            if (done.returncode != 1 or "Traceback" in text or not items
                    or not all(line.startswith("  - not done yet: Task") for line in items)):
                problems.append(f"labs/check {n} on the starters: expected only 'not done yet' "
                                f"lines, got exit {done.returncode}:\n{text.strip()}")
            done, text = run(copy, "labs/check", n, "--solution", "--radkit", radkit)
            if (done.returncode == 0 or "Traceback" in text
                    or "this copy of the labs has no reference solutions" not in text):
                problems.append(f"labs/check {n} --solution: expected the refusal naming the "
                                f"missing solutions, got exit {done.returncode}:\n{text.strip()}")

        # grade.py: one student with every lab's starters, graded without labs/instructor/hidden.
        subs, out = Path(tmp) / "hand-ins", Path(tmp) / "grades"
        for lab in labs:
            (subs / "ada" / lab.name).mkdir(parents=True)
            for path in lab.glob("*.py"):
                if path.name not in ("check_lab.py", "study.py"):
                    shutil.copy2(path, subs / "ada" / lab.name / path.name)
        for extra in ([], ["--no-hidden"]):
            done, text = run(copy, "labs/grade.py", subs, "--out", out, "--radkit", radkit,
                             "--timeout", 120, *extra)
            if done.returncode != 0 or "Traceback" in text:
                problems.append(f"grade.py {' '.join(extra)} without labs/instructor/ failed "
                                f"({done.returncode}):\n{text.strip()}")
                continue
            with open(out / "grades.csv") as f:
                rows = list(csv.DictReader(f))
            bad = [(r["lab"], r["total"], r["status"]) for r in rows
                   if r["total"] != "0" or r["status"] != "failed"]
            if len(rows) != len(labs) or bad:
                problems.append(f"grade.py {' '.join(extra)}: {len(rows)} rows, expected "
                                f"{len(labs)} starters at 0 points, failed; wrong: {bad}")
            feedback = (out / "feedback-ada.txt").read_text()
            if "(hidden case)" in feedback or "not done yet: Task 1" not in feedback:
                problems.append("feedback-ada.txt: expected the checks' 'not done yet' lines "
                                "and no hidden case")
        done, text = run(copy, "labs/grade.py", Path(tmp) / "nowhere", "--out", out)
        if done.returncode == 0 or not re.search(r"nowhere is not a folder.*Fix:", text):
            problems.append(f"grade.py on a missing folder: expected its refusal, got "
                            f"{done.returncode}:\n{text.strip()}")
    for p in problems:
        print(f"FAIL: {p}")
    print(f"without instructor: {'FAILED' if problems else 'all passed'}")
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    os.environ.pop("RADKIT", None)  # --radkit decides, as the CMake test passes it
    main()
