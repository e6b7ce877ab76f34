#!/usr/bin/env bash
# Build the libFuzzer targets of tests/fuzz with clang under ASan+UBSan into build-fuzz/, then for
# each target:
#   1. replay its committed corpus, tests/fuzz/corpus/<target>/: the seeds and every input that
#      once found a defect (regression inputs), each run once;
#   2. explore from those seeds for the given number of inputs (default 50000) or seconds
#      (default 90), whichever ends first, with a fixed seed and the VTK token dictionary for the
#      VTK readers: every run, here or in CI, tries the same inputs in the same order, so a
#      failure in CI is reproduced by running the script.
# Fails on the first target that finds a crash, a leak, a timeout or a sanitizer report; the input
# that did it is kept in build-fuzz/artifacts/<target>/. Once the defect is fixed, commit that
# input to tests/fuzz/corpus/<target>/ so that every later replay runs it.
#   scripts/fuzz.sh [inputs per target] [seconds per target]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-50000}
seconds=${2:-90}
TETRAY_SETUP_INSTALL_ONLY=1 scripts/setup.sh
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DTETRAY_FUZZ=ON -DTETRAY_BUILD_TESTS=OFF -DTETRAY_BUILD_BENCHMARKS=OFF
cmake --build build-fuzz
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan.supp
for target in fuzz_config fuzz_vtu fuzz_vtu_counts fuzz_pvtu fuzz_pvd fuzz_views; do
  seeds=tests/fuzz/corpus/$target
  corpus=build-fuzz/corpus/$target  # new inputs; emptied first, so a run depends on the seeds
  artifacts=build-fuzz/artifacts/$target
  rm -rf "$corpus"
  mkdir -p "$corpus" "$artifacts"
  # fuzz_views starts MPI, whose own allocations LeakSanitizer would report (see
  # tests/support/lsan_options.cpp); the other targets keep the leak check.
  leaks=1
  [ "$target" = fuzz_views ] && leaks=0
  options=(-timeout=20 -rss_limit_mb=4096 -artifact_prefix="$artifacts/")
  case $target in fuzz_vtu | fuzz_pvtu | fuzz_pvd) options+=(-dict=tests/fuzz/vtk.dict) ;; esac
  echo "== $target: replay of $(ls "$seeds" | wc -l) committed inputs"
  ASAN_OPTIONS=detect_leaks=$leaks build-fuzz/bin/$target "${options[@]}" "$seeds"/*
  echo "== $target: $runs new inputs (at most ${seconds} s)"
  ASAN_OPTIONS=detect_leaks=$leaks build-fuzz/bin/$target "$corpus" "$seeds" "${options[@]}" \
    -seed=1 -runs="$runs" -max_total_time="$seconds" -print_final_stats=1
done
