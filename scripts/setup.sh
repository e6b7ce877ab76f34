#!/usr/bin/env bash
# Install every Debian 12 package tetray needs, then configure and build in
# Release into build/ (executables in build/bin/). Idempotent: a second run
# installs nothing and rebuilds only what changed.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config git clang-format
  libvtk9-dev libopenexr-dev libopenmpi-dev openmpi-bin libtbb-dev
  libyaml-cpp-dev libgtest-dev libgmock-dev libbenchmark-dev libpng-dev
  libxsimd-dev libembree-dev python3-imath libeigen3-dev libcli11-dev gfortran
  libjsoncpp-dev clang libclang-rt-14-dev libdeflate-dev
  libavcodec-dev libavformat-dev libswscale-dev libavutil-dev
  pybind11-dev python3-dev python3-numpy python3-mpi4py python3-png python3-dolfinx
  libfreetype-dev fonts-dejavu-core chromium
  python3-matplotlib python3-pil xvfb xauth libgl1-mesa-dri
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

[ "${TETRAY_SETUP_INSTALL_ONLY:-0}" = 1 ] && exit 0
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release ${TETRAY_CMAKE_ARGS:-}
cmake --build build
