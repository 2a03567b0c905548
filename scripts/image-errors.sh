#!/usr/bin/env bash
# RMSE against time for the image modes on the Cornell box (docs/images.md's tables):
# two independent long path-traced references, then each mode measured against them.
# Usage: scripts/image-errors.sh [OUT_DIR] [REFERENCE_SPP]   (needs a built tree; ~10 min)
# Columns: CPU seconds (user + system, radiosity solution included: steadier than wall time
# on a shared machine), then relative RMSE in % over the non-emitting surfaces away from
# edges, along edges, and over every pixel.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/image-errors}
refspp=${2:-1024}
radkit=$PWD/build/apps/radkit
size=256x256
mkdir -p "$out"
for seed in 101 102; do
  [ -f "$out/ref$seed.pfm" ] || $radkit render --spp "$refspp" --seed "$seed" --size $size --out "$out/ref$seed.pfm" >/dev/null
done
refs="--reference $out/ref101.pfm --reference $out/ref102.pfm"
run() {  # name, then render options; prints one row of the table
  local name=$1 cpu
  shift
  TIMEFORMAT='%U %S'
  cpu=$( { time $radkit render --size $size "$@" $refs --report "$out/$name.json" --out "$out/$name.pfm" \
             >"$out/$name.txt" 2>/dev/null; } 2>&1 | awk '{ print $1 + $2 }')
  awk -v n="$name" -v t="$cpu" '$1 == "rmse" && $2 == "all:" { a = $3 } $1 == "rmse" && $2 == "surfaces:" { s = $3 }
      $1 == "rmse" && $2 == "edges:" { e = $3 } END { printf "%s\t%.1f\t%s\t%s\t%s\n", n, t, s, e, a }' "$out/$name.txt"
}
echo -e "mode\tcpu_s\tsurfaces_%\tedges_%\tall_%"
run flat --shading radiosity
run smooth --shading radiosity --smooth
run smooth-4000 --shading radiosity --smooth --patches 4000
for spp in 16 64 256; do run "final-gather-$spp" --shading final-gather --spp $spp; done
run final-gather-unguided-64 --shading final-gather --spp 64 --unguided
run final-gather-2000-128 --shading final-gather --spp 128 --patches 2000
run final-gather-4000-256 --shading final-gather --spp 256 --patches 4000
for sampler in independent stratified sobol; do
  for spp in 16 64 256; do run "path-$sampler-$spp" --shading path-trace --sampler $sampler --spp $spp; done
done
for spp in 16 64 256; do
  run "path-sobol-solid-angle-$spp" --shading path-trace --light-sampling solid-angle --spp $spp
done
run path-sobol-1024 --shading path-trace --spp 1024
