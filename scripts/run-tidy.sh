#!/usr/bin/env bash
# clang-tidy with the repository's .clang-tidy over every source file of the folders in
# scripts/folders.txt (not tests/, whose gtest macros trip checks the library code is held
# to, nor fuzz/, built only by clang with RADKIT_FUZZ), from build-tidy/compile_commands.json.
# Prints findings and exits 1 on any. A file whose preprocessed text has not changed since a
# clean run is not checked again (scripts/tidy-cached.py), so CI pays the whole tree's 12
# minutes once and then only for what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-tidy -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  -DRADKIT_TESTS=OFF >/dev/null
folders=$(awk '/^[0-9]/ { print $2 }' scripts/folders.txt)
files=$(for f in $folders; do git ls-files "$f/*.cpp"; done)
python3 scripts/tidy-cached.py build-tidy $files
