#!/usr/bin/env bash
# The README's first command: installs, builds and runs the main job on the Cornell box.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/apps/radkit mesh data/cornell-box.json --patches 4000 --out out/cornell-box
