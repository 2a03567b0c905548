#!/usr/bin/env bash
# clang-format (the repository's .clang-format) over every C++ file git tracks: lists the files
# whose formatting differs and exits 1. `bash scripts/check-format.sh --fix` rewrites them.
set -euo pipefail
cd "$(dirname "$0")/.."
files=$(git ls-files '*.h' '*.cpp')
if [[ "${1:-}" == "--fix" ]]; then
  clang-format -i $files
  exit 0
fi
bad=$(clang-format --dry-run $files 2>&1 | grep -E '^[^ :]+:[0-9]+:[0-9]+: (warning|error):' |
  cut -d: -f1 | sort -u || true)
if [[ -n "$bad" ]]; then
  echo "clang-format: these files differ from .clang-format (fix: bash scripts/check-format.sh --fix):"
  echo "$bad"
  exit 1
fi
echo "clang-format: $(echo "$files" | wc -w) files formatted"
