#!/usr/bin/env bash
# The test suite under AddressSanitizer, UndefinedBehaviorSanitizer and LeakSanitizer (clang,
# -O1 -g) in build-sanitize/, which also builds the fuzz targets (RADKIT_FUZZ, fuzz/).
# tests/lsan.supp names the third-party leaks to ignore. The GL viewer test runs without leak
# detection: Mesa's llvmpipe leaks from code it compiles at run time, whose stack frames have
# no module a suppression could name.
# The Python module is left out: an ASan runtime cannot be loaded into an uninstrumented python3.
# RADKIT_SANITIZE_SKIP names test folders to leave out (CI: those that exercise radkit's own
# code least, see docs/robustness.md); by default every folder of scripts/folders.txt runs.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
skip=${RADKIT_SANITIZE_SKIP:-}
CC=clang CXX=clang++ cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DRADKIT_TESTS=ON -DRADKIT_TEST_FOLDERS=all -DRADKIT_TEST_FOLDERS_SKIP="$skip" \
  -DRADKIT_WERROR="${RADKIT_WERROR:-OFF}" -DRADKIT_SANITIZE="address;undefined" -DRADKIT_FUZZ=ON -DRADKIT_PYTHON=OFF \
  -DCMAKE_UNITY_BUILD="${RADKIT_UNITY:-ON}" -DCMAKE_UNITY_BUILD_BATCH_SIZE=8 >/dev/null
cmake --build build-sanitize -j"${RADKIT_JOBS:-2}"
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp" UBSAN_OPTIONS=print_stacktrace=1
ASAN_OPTIONS=detect_leaks=1 ctest --test-dir build-sanitize --output-on-failure -j"${RADKIT_JOBS:-2}" \
  --timeout 900 -E viewer_screenshots -LE long
if [[ ";$skip;" != *";viewer;"* ]]; then
  ASAN_OPTIONS=detect_leaks=0 ctest --test-dir build-sanitize --output-on-failure --timeout 900 -R viewer_screenshots
fi
