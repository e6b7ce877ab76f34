#!/usr/bin/env bash
# Build (through setup.sh) and run the whole test suite with ctest.
#   scripts/test.sh             Release build in build/, every test
#   scripts/test.sh --sanitize  ASan+UBSan build in build-asan/, unit tests only
# No test may skip: ctest counts the skipped ones (a GoogleTest or unittest skip is one too) and
# the run fails unless there are TETRAY_EXPECTED_SKIPS of them (default 0), listed by name.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)

# ctest over build directory $1 with the remaining arguments, then the skip count.
run_ctest() {
  local dir=$1
  shift
  local status=0
  ctest --test-dir "$dir" --output-on-failure -j "$jobs" --output-junit ctest.xml "$@" || status=$?
  local skipped expected=${TETRAY_EXPECTED_SKIPS:-0}
  skipped=$(grep -c '<skipped ' "$dir/ctest.xml" || true)
  echo "skipped tests in $dir: $skipped (expected $expected)"
  if [ "$skipped" -ne "$expected" ]; then
    grep -B1 '<skipped ' "$dir/ctest.xml" | sed -n 's/.*<testcase name="\([^"]*\)".*/  skipped: \1/p'
    status=1
  fi
  return "$status"
}
if [ "${1:-}" = "--sanitize" ]; then
  TETRAY_SETUP_INSTALL_ONLY=1 scripts/setup.sh
  # -O1, as AddressSanitizer's documentation suggests: GCC compiles the kernels of the three
  # instruction sets with the sanitizers in half the time it takes at -O2, most of CI's time.
  # -g1: line tables only, which is all a sanitizer's stack trace reads (file:line stays); a
  # kernel file compiled in 25 s instead of 37 with -g, a test file in 7 s instead of 9.
  # The kernels are compiled once, for baseline x86-64 (portable), like the baseline copy the
  # Release build's tests call: the instruction-set copies of a dispatch build are the same
  # source, tested against each other and against the baseline in the Release build.
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTETRAY_SANITIZE=ON \
    -DTETRAY_SIMD_TARGET=portable \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DTETRAY_BUILD_BENCHMARKS=OFF ${TETRAY_CMAKE_ARGS:-}
  cmake --build build-asan
  # Open MPI's own allocations are reported as leaks by LeakSanitizer; the leak check is
  # about tetray, so it stays on for the unit tests that do not start MPI.
  export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
  export ASAN_OPTIONS=detect_leaks=1
  run_ctest build-asan -L unit
  exit 0
fi
scripts/setup.sh
run_ctest build
