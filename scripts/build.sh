#!/usr/bin/env bash
# Installs the Debian packages (idempotent) and builds radkit in Release into build/.
# RADKIT_WERROR=ON (CI sets it) turns warnings into errors. Unity batches of 8 files build the
# tree cold in about 3 min on 2 cores; RADKIT_UNITY=OFF when editing one file at a time.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DRADKIT_TESTS=ON \
  -DRADKIT_WERROR="${RADKIT_WERROR:-OFF}" -DCMAKE_UNITY_BUILD="${RADKIT_UNITY:-ON}" \
  -DCMAKE_UNITY_BUILD_BATCH_SIZE=8 \
  -DRADKIT_TEST_FOLDERS=all -DRADKIT_TEST_FOLDERS_SKIP= >/dev/null
cmake --build build -j"${RADKIT_JOBS:-2}"
