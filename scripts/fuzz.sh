#!/usr/bin/env bash
# Build the libFuzzer targets of tests/fuzz with clang under ASan+UBSan into build-fuzz/, then
# run each for the given number of inputs (default 50000) from the seed corpus of
# tests/fuzz/corpus/<target>/, with a fixed seed and a fresh corpus: every run, here or in CI,
# tries the same inputs in the same order, so a failure in CI is reproduced by running the
# script. A target that has not finished after `seconds` (default 180) stops there, having tried
# the first part of the same sequence. Fails on the first target that finds a crash, a leak, a
# timeout or a sanitizer report; the input that did it is kept in build-fuzz/artifacts/<target>/.
#   scripts/fuzz.sh [inputs per target] [seconds per target]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-50000}
seconds=${2:-180}
TETRAY_SETUP_INSTALL_ONLY=1 scripts/setup.sh
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DTETRAY_FUZZ=ON -DTETRAY_BUILD_TESTS=OFF -DTETRAY_BUILD_BENCHMARKS=OFF
cmake --build build-fuzz
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan.supp
for target in fuzz_config fuzz_vtu fuzz_pvtu fuzz_pvd fuzz_views; do
  # New inputs go to build-fuzz/corpus (the first directory, emptied first, so that the run
  # depends only on the seed); the seeds stay as committed.
  corpus=build-fuzz/corpus/$target
  artifacts=build-fuzz/artifacts/$target
  rm -rf "$corpus"
  mkdir -p "$corpus" "$artifacts"
  # fuzz_views starts MPI, whose own allocations LeakSanitizer would report (see
  # tests/support/lsan_options.cpp); the other targets keep the leak check.
  leaks=1
  [ "$target" = fuzz_views ] && leaks=0
  echo "== $target: $runs inputs (at most ${seconds} s)"
  ASAN_OPTIONS=detect_leaks=$leaks build-fuzz/bin/$target "$corpus" "tests/fuzz/corpus/$target" \
    -seed=1 -runs="$runs" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 \
    -print_final_stats=1 \
    -artifact_prefix="$artifacts/"
done
