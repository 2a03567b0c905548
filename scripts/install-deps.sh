#!/usr/bin/env bash
# Installs the Debian packages radkit builds and tests with. Idempotent: packages already
# present are skipped, and apt is not touched at all when nothing is missing.
set -euo pipefail

packages=(
  build-essential cmake ninja-build ccache pkg-config
  libcgal-dev libopenmesh-dev libembree-dev libtbb-dev
  nlohmann-json3-dev libcli11-dev libtinyobjloader-dev libstb-dev
  libgtest-dev libbenchmark-dev
  libvtk9-dev xvfb xauth libplplot-dev plplot-driver-cairo libnanoflann-dev
  libopenexr-dev  # render --out x.exr
  clang libclang-rt-14-dev  # scripts/run-sanitizers.sh
  clang-format  # scripts/check-format.sh (CI)
  clang-tidy  # scripts/run-tidy.sh (CI)
  pybind11-dev python3-dev python3-numpy python3-scipy python3-pytest python3-matplotlib  # python/, labs/
  python3-nbclient python3-nbformat python3-ipykernel  # labs/run_notebook.py
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
