#!/usr/bin/env bash
# Install the Debian 12 packages tetray needs, then configure and build in Release into build/
# (executables in build/bin/). Idempotent: a second run installs nothing and rebuilds only what
# changed.
#   scripts/setup.sh          everything: the library, tools, benchmarks, Python package and
#                             tests, with every package they need (the test command)
#   scripts/setup.sh --demo   only what the demo needs: the library without its VTK bridge and
#                             movie writer, and the mini-solver (the main command; minutes, not a
#                             quarter hour, on a fresh machine)
# Both use build/: a later full run reuses the demo's objects and adds the rest.
# TETRAY_SETUP_INSTALL_ONLY=1 installs the packages and stops; TETRAY_CMAKE_ARGS adds options.
set -euo pipefail
cd "$(dirname "$0")/.."

scope=all
case "${1:-}" in
  --demo) scope=demo ;;
  "") ;;
  *) echo "usage: scripts/setup.sh [--demo]" >&2; exit 2 ;;
esac

# What the library and the mini-solver need (compilers, MPI, the render stages' libraries).
demo_packages=(
  build-essential cmake ninja-build pkg-config gfortran
  libopenmpi-dev openmpi-bin libtbb-dev libxsimd-dev libyaml-cpp-dev libeigen3-dev libcli11-dev
  libopenexr-dev libpng-dev libdeflate-dev libfreetype-dev fonts-dejavu-core
)
# The rest: the VTK bridge and the tools' VTK files (VTK alone is about 400 packages), movies
# (FFmpeg), the benchmarks' peers (Embree, VTK's renderers), the tests (GoogleTest, Chromium for
# the viewer page, DOLFINx, the Python package and its checks, QEMU's user mode for a CPU without
# x86-64-v2), the fuzzers (clang), formatting, and SimGrid's SMPI, in which the compositor runs
# at thousands of simulated ranks (scripts/scaling.sh; a test checks it against real runs).
test_packages=(
  git clang-format libvtk9-dev libavcodec-dev libavformat-dev libswscale-dev libavutil-dev
  libgtest-dev libgmock-dev libbenchmark-dev libembree-dev libjsoncpp-dev python3-imath
  clang libclang-rt-14-dev qemu-user libsimgrid-dev
  pybind11-dev python3-dev python3-numpy python3-mpi4py python3-png python3-dolfinx
  chromium python3-matplotlib python3-pil xvfb xauth libgl1-mesa-dri
  # gmsh 4.8 with OpenCASCADE for the curved-part example (examples/gmsh/): meshes a CAD part
  # into quadratic tets in its tests
  python3-gmsh
  # deal.II 9.4 (MPI, p4est, Trilinos) for the deal.II example's tests: 138 packages, 177 MB to
  # fetch, 1.4 GB on disk, 47 s to install beside the packages above
  libdeal.ii-dev
)

packages=("${demo_packages[@]}")
[ "$scope" = all ] && packages+=("${test_packages[@]}")
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
if [ "$scope" = demo ]; then
  # A build directory configured in full before (tests on, which needs everything else on; also
  # in a cache from before these options) stays so: the demo then builds only its target.
  options=()
  if ! grep -qs '^TETRAY_BUILD_TESTS:BOOL=ON' build/CMakeCache.txt; then
    options=(-DTETRAY_VTK=OFF -DTETRAY_MOVIES=OFF -DTETRAY_BUILD_TOOLS=OFF
      -DTETRAY_BUILD_TESTS=OFF -DTETRAY_BUILD_BENCHMARKS=OFF -DTETRAY_BUILD_PYTHON=OFF)
  fi
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${options[@]}" ${TETRAY_CMAKE_ARGS:-}
  cmake --build build --target tetray-minisolver
else
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DTETRAY_VTK=ON -DTETRAY_MOVIES=ON \
    -DTETRAY_BUILD_TOOLS=ON -DTETRAY_BUILD_TESTS=ON -DTETRAY_BUILD_BENCHMARKS=ON \
    -DTETRAY_BUILD_PYTHON=ON ${TETRAY_CMAKE_ARGS:-}
  cmake --build build
fi
