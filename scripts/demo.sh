#!/usr/bin/env bash
# The README's main command: install and build only what the demo needs (scripts/setup.sh
# --demo: the library and the mini-solver, no tests or tools), then run the deforming, heating
# cantilever beam of configs/demo.yaml on two ranks. Images, the Cinema database and the timing
# log land in out/demo.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --demo
mpi_flags=(--oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi_flags+=(--allow-run-as-root)
time mpirun -np 2 "${mpi_flags[@]}" build/bin/tetray-minisolver configs/demo.yaml
echo "images: out/demo/{beam,temperature,beam_cut,heat_volume}/*.png; viewer: out/demo/index.html; log: out/demo/tetray_log.csv"
