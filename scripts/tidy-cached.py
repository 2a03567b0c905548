#!/usr/bin/env python3
"""clang-tidy over the given source files, skipping each one whose preprocessed text, together
with .clang-tidy and the clang-tidy version, passed before: a translation unit that has not
changed cannot have new findings. The cache is a folder of empty files named by that hash
(RADKIT_TIDY_CACHE, by default ~/.cache/radkit-tidy), so it survives a fresh clone as ccache
does; a file with findings is not cached. Usage: tidy-cached.py BUILD_DIR FILE...
Prints the findings and a summary; exits 1 on any finding."""
import hashlib
import json
import os
import re
import shlex
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def preprocess_command(entry):
    args = shlex.split(entry["command"]) if "command" in entry else list(entry["arguments"])
    if Path(args[0]).name == "ccache":
        args = args[1:]
    out = []
    skip = False
    for a in args:
        if skip:
            skip = False
            continue
        if a in ("-o", "-MF", "-MT", "-MQ"):
            skip = True
            continue
        if a in ("-c", "-MD", "-MMD"):
            continue
        out.append(a)
    # -P drops line markers, so the text (and the hash) does not depend on where the clone is.
    return out + ["-E", "-P", "-o", "-"]


def main():
    build = Path(sys.argv[1])
    files = [str((ROOT / f).resolve()) for f in sys.argv[2:]]
    database = {str(Path(e["directory"], e["file"]).resolve()): e
                for e in json.loads((build / "compile_commands.json").read_text())}
    missing = [f for f in files if f not in database]
    if missing:
        print("tidy: not in the compile database (configure build-tidy again): " +
              " ".join(missing), file=sys.stderr)
        return 1
    version = subprocess.run(["clang-tidy", "--version"], capture_output=True, text=True).stdout
    salt = (ROOT / ".clang-tidy").read_text() + version
    cache = Path(os.environ.get("RADKIT_TIDY_CACHE", Path.home() / ".cache" / "radkit-tidy"))
    cache.mkdir(parents=True, exist_ok=True)

    def key(f):
        entry = database[f]
        text = subprocess.run(preprocess_command(entry), cwd=entry["directory"],
                              capture_output=True, check=True).stdout
        h = hashlib.sha256(salt.encode())
        h.update(os.path.relpath(f, ROOT).encode())
        h.update(text)
        return h.hexdigest()

    jobs = os.cpu_count() or 2
    with ThreadPoolExecutor(jobs) as pool:
        keys = dict(zip(files, pool.map(key, files)))
    todo = [f for f in files if not (cache / keys[f]).exists()]

    def tidy(f):
        run = subprocess.run(["clang-tidy", "-p", str(build), "-quiet", f], capture_output=True,
                             text=True)
        text = re.sub(r"\x1b\[[0-9;]*m", "", run.stdout + run.stderr)  # colour codes
        found = [l for l in text.splitlines() if re.search(r"(warning|error): ", l)]
        if run.returncode != 0 and not found:
            found = [f"{f}: clang-tidy exited {run.returncode}: {text[-2000:]}"]
        if not found:
            (cache / keys[f]).touch()  # this translation unit is clean
        return found

    with ThreadPoolExecutor(jobs) as pool:
        findings = sorted(set(l for found in pool.map(tidy, todo) for l in found))
    for line in findings:
        print(line)
    print(f"clang-tidy: {len(findings)} findings; {len(todo)} of {len(files)} files checked, "
          f"{len(files) - len(todo)} unchanged since a clean run (cache {cache})")
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
