#!/usr/bin/env bash
# Runs each libFuzzer target of fuzz/ (scene JSON, OBJ + MTL, PLY, OFF, STL, the Python
# module's arrays, run folders as the viewer reads them) for SECONDS
# (default 20) from seeds made out of data/ (fuzz/make_seeds.py). Needs the sanitizer tree
# that scripts/run-sanitizers.sh builds (build-sanitize/, or BUILD_DIR). Corpora grow in
# out/fuzz/corpus/<format>/; a finding leaves its input in out/fuzz/ and fails the script.
# Usage: scripts/run-fuzz.sh [SECONDS] [FORMAT...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
shift || true
formats=("$@")
[ ${#formats[@]} -gt 0 ] || formats=(json obj ply off stl python_arrays run_folder)
build=${BUILD_DIR:-build-sanitize}
cmake --build "$build" -j"${RADKIT_JOBS:-2}" --target fuzz
out=out/fuzz
mkdir -p "$out/seeds"
# Before make_seeds.py: it runs the sanitizer build of radkit for the run-folder seeds, whose
# third-party leaks tests/lsan.supp names (without it those runs fail and the seeds are lost).
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp" UBSAN_OPTIONS=print_stacktrace=1
python3 fuzz/make_seeds.py "$out/seeds"
for f in "${formats[@]}"; do
  mkdir -p "$out/corpus/$f"
  echo "fuzz_$f: ${seconds} s"
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: memory the file cannot justify.
  "$build/fuzz/fuzz_$f" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=1024 -max_len=65536 \
    -print_final_stats=1 -artifact_prefix="$out/$f-" "$out/corpus/$f" "$out/seeds/$f" 2>"$out/$f.log" ||
    { tail -n 60 "$out/$f.log"; echo "fuzz_$f: finding, input saved as $out/$f-*"; exit 1; }
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$out/$f.log" || true
done
