#!/usr/bin/env bash
# clang-tidy with the repository's .clang-tidy over every source file of the folders in
# scripts/folders.txt (not tests/, whose gtest macros trip checks the library code is held
# to, nor fuzz/, built only by clang with RADKIT_FUZZ). Uses build-tidy/compile_commands.json; prints findings, exits 1 on any.
# Takes about 10 minutes on 2 cores, so CI does not run it; docs/development.md says when to.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-tidy -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  -DRADKIT_TESTS=OFF >/dev/null
folders=$(awk '/^[0-9]/ { print $2 }' scripts/folders.txt)
files=$(for f in $folders; do git ls-files "$f/*.cpp"; done)
log=$(mktemp)
run-clang-tidy -quiet -p build-tidy -j "$(nproc)" $files >"$log" 2>&1 || true
grep -E "(warning|error): " "$log" | sort -u | tee build-tidy/findings.txt
count=$(wc -l <build-tidy/findings.txt)
rm -f "$log"
echo "clang-tidy: $count findings in $(echo "$files" | wc -w) files"
[[ "$count" -eq 0 ]]
