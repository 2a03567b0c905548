#!/usr/bin/env python3
"""Fails when a source file includes a header from a folder on its own or a higher floor
(scripts/folders.txt), naming the file, the line and the two floors, or when .clang-tidy's
header filter leaves a folder out. tests/, fuzz/ and docs' examples sit above every floor and
are not checked."""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')


def floors(root):
    result = {}
    for line in (root / "scripts" / "folders.txt").read_text().splitlines():
        line = line.split("#", 1)[0].split()
        if line:
            result[line[1]] = int(line[0])
    return result


def main():
    # --root DIR checks another tree (the test of this check gives it one with a climbing include).
    root = Path(sys.argv[2]).resolve() if sys.argv[1:2] == ["--root"] else ROOT
    floor = floors(root)
    problems = []
    checked = 0
    for folder, level in floor.items():
        for path in sorted((root / folder).rglob("*")):
            if path.suffix not in (".h", ".cpp", ".hpp", ".cc") or "tests" in path.parts:
                continue
            checked += 1
            for number, text in enumerate(path.read_text(errors="replace").splitlines(), 1):
                m = INCLUDE.match(text)
                if not m or m.group(1) == folder or m.group(1) not in floor:
                    continue
                other = m.group(1)
                if floor[other] >= level:
                    problems.append(
                        f"{path.relative_to(root)}:{number}: includes {other}/ (floor "
                        f"{floor[other]}) from {folder}/ (floor {level}); a folder may include "
                        f"only lower floors. Fix: move what is shared down, or pass it in "
                        f"from above (scripts/folders.txt, docs/architecture.md)")
    # .clang-tidy cannot read folders.txt: its header filter must name every folder.
    tidy = root / ".clang-tidy"
    if tidy.exists():
        m = re.search(r"^HeaderFilterRegex: '/\(([a-z_|]+)\)", tidy.read_text(), re.MULTILINE)
        named = set(m.group(1).split("|")) if m else set()
        for folder in floor:
            if folder not in named:
                problems.append(f".clang-tidy: HeaderFilterRegex does not name {folder}/, so "
                                f"clang-tidy skips its headers. Fix: add it to the regex")
    for p in problems:
        print(p)
    print(f"check-layers: {checked} files in {len(floor)} folders, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
