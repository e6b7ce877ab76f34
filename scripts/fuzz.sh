#!/usr/bin/env bash
# Build the libFuzzer targets of tests/fuzz with clang under ASan+UBSan into build-fuzz/, then
# run each for the given time (seconds, default 60), starting from the seed corpus of
# tests/fuzz/corpus/<target>/. Fails on the first target that finds a crash, a leak, a timeout
# or a sanitizer report; the input that did it is kept in build-fuzz/artifacts/<target>/.
#   scripts/fuzz.sh [seconds per target]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
TETRAY_SETUP_INSTALL_ONLY=1 scripts/setup.sh
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DTETRAY_FUZZ=ON -DTETRAY_BUILD_TESTS=OFF -DTETRAY_BUILD_BENCHMARKS=OFF
cmake --build build-fuzz
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan.supp
for target in fuzz_config fuzz_vtu fuzz_pvtu fuzz_pvd fuzz_views; do
  # New inputs go to build-fuzz/corpus (the first directory); the seeds stay as committed.
  corpus=build-fuzz/corpus/$target
  artifacts=build-fuzz/artifacts/$target
  mkdir -p "$corpus" "$artifacts"
  # fuzz_views starts MPI, whose own allocations LeakSanitizer would report (see
  # tests/support/lsan_options.cpp); the other targets keep the leak check.
  leaks=1
  [ "$target" = fuzz_views ] && leaks=0
  echo "== $target: ${seconds} s"
  ASAN_OPTIONS=detect_leaks=$leaks build-fuzz/bin/$target "$corpus" "tests/fuzz/corpus/$target" \
    -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 -print_final_stats=1 \
    -artifact_prefix="$artifacts/"
done
