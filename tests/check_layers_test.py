#!/usr/bin/env python3
"""scripts/check-layers.py passes on the repository and fails, naming the file, the line and
the floors, on a tree where a lower floor includes a higher one or two folders of one floor
include each other, or where .clang-tidy's header filter leaves a folder out."""
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CHECK = ROOT / "scripts" / "check-layers.py"


def check(*args):
    return subprocess.run([sys.executable, str(CHECK), *args], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True)


def main():
    ok = check()
    assert ok.returncode == 0, ok.stdout
    assert "0 problems" in ok.stdout, ok.stdout
    with tempfile.TemporaryDirectory() as tmp:
        tree = Path(tmp)
        (tree / "scripts").mkdir()
        shutil.copy(ROOT / "scripts" / "folders.txt", tree / "scripts")
        for folder in ("util", "solvers", "bsdf", "apps"):
            (tree / folder).mkdir()
        (tree / "util" / "good.h").write_text('#include <vector>\n#include "util/other.h"\n')
        (tree / "solvers" / "fine.cpp").write_text('#include "util/good.h"\n')
        (tree / "util" / "bad.h").write_text('#pragma once\n#include "apps/options.h"\n')
        (tree / "bsdf" / "sideways.cpp").write_text('// same floor\n#include "solvers/x.h"\n')
        # Flag words in a library's message, and three strings that may keep them: a comment,
        # a whole radkit command, and a front end's own message.
        (tree / "solvers" / "says.cpp").write_text(
            'auto a = "x";\nthrow E("raise --max-iterations or --tol");\n'
            '// the CLI sets --tol\nauto b = "radkit run --method hierarchical";\n')
        (tree / "apps" / "cli.cpp").write_text('auto c = "give --out";\n')
        # The repository's .clang-tidy without python/ in its header filter.
        tidy = (ROOT / ".clang-tidy").read_text().replace("|python|", "|")
        (tree / ".clang-tidy").write_text(tidy)
        bad = check("--root", str(tree))
        assert bad.returncode == 1, bad.stdout
        assert re.search(r"util/bad\.h:2: includes apps/ \(floor \d+\) from util/ \(floor 0\)",
                         bad.stdout), bad.stdout
        assert "bsdf/sideways.cpp:2: includes solvers/ (floor 1) from bsdf/ (floor 1)" in bad.stdout, bad.stdout
        assert ".clang-tidy: HeaderFilterRegex does not name python/" in bad.stdout, bad.stdout
        assert ('solvers/says.cpp:2: a library message says --max-iterations, a command-line '
                'flag. Fix: name the setting, setting("max_iterations")') in bad.stdout, bad.stdout
        assert "4 problems" in bad.stdout, bad.stdout
    print("check-layers: passes on the repository, fails on climbing includes")


if __name__ == "__main__":
    main()
