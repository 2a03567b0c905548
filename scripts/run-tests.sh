#!/usr/bin/env bash
# The README's test command: installs, builds and runs the whole suite with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"${RADKIT_JOBS:-2}" --timeout 600
