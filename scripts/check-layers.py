#!/usr/bin/env python3
"""Fails when a source file includes a header from a folder on its own or a higher floor
(scripts/folders.txt), naming the file, the line and the two floors; when a library's string
speaks in command-line flags ("raise --tol") instead of naming the setting (util/setting_names.h:
setting("tol")); or when .clang-tidy's header filter leaves a folder out. tests/, fuzz/ and
docs' examples sit above every floor and are not checked."""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')
LITERAL = re.compile(r'"((?:[^"\\\n]|\\.)*)"')
FLAG = re.compile(r'(?<![\w-])--[a-z][a-z0-9-]*')
# The front ends spell settings as flags or keywords themselves.
FRONT_ENDS = {"apps", "python"}


def flag_words(text):
    """A flag in a string literal of a code line; a whole command line ("radkit run --method
    hierarchical", a `quoted` command, a script's) is a command, not a setting."""
    if text.lstrip().startswith("//"):
        return None
    for m in LITERAL.finditer(text):
        body = m.group(1)
        if "radkit " in body or "`" in body or ".py " in body:
            continue
        f = FLAG.search(body)
        if f:
            return f.group(0)
    return None


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
                flag = None if folder in FRONT_ENDS else flag_words(text)
                if flag:
                    key = flag[2:].replace("-", "_")
                    problems.append(
                        f"{path.relative_to(root)}:{number}: a library message says {flag}, a "
                        f"command-line flag. Fix: name the setting, setting(\"{key}\") "
                        f"(util/setting_names.h), so each front end spells it its own way")
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
