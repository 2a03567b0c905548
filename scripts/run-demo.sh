#!/usr/bin/env bash
# The README's first command: installs, builds and runs the main job on the Cornell box.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/apps/radkit run --out out/cornell-box
