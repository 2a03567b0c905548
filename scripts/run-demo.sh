#!/usr/bin/env bash
# The README's first command: installs, builds and runs the main job on the Cornell box.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/apps/radkit run --out out/cornell-box
echo "radkit: pictures and numbers are in out/cornell-box/ (render.png, report.json; docs/run.md)."
echo "radkit: next, the lab exercises start at labs/README.md; the Python module at docs/python.md."
