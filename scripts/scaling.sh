#!/usr/bin/env bash
# The compositor at thousands of ranks in SimGrid's SMPI (docs/scaling.md). Builds the
# compositor and tetray-composite-bench with smpicxx into build-smpi/ (-DTETRAY_SMPI=ON), next to
# the normal build's bench in build/ (scripts/setup.sh), then
#   scripts/scaling.sh calibrate   real mpirun against the simulator of this machine at 2, 4 and 8
#                                  ranks: times per round and total, and the root images' hashes
#   scripts/scaling.sh sweep       16 to 4,096 ranks (and past, where noted) on the cluster and
#                                  Blue Gene/P platforms: sweep.csv and sweep.png
#   scripts/scaling.sh bluegene    sparse 64-megapixel images on the Blue Gene/P in Z-order, the
#                                  cube seen along z and along x, 1,024 to 32,768 ranks:
#                                  bluegene_p_zorder.csv
#   scripts/scaling.sh point PLATFORM RANKS [bench options...]   one simulated run
#   scripts/scaling.sh costs       the per-pixel costs the sweep injects (scan, encode, composite,
#                                  copy, ns), with TETRAY_SCALING_THREADS threads per rank
# Results go to out/scaling/ (TETRAY_SCALING_OUT). Every simulated figure is deterministic: one
# run each.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${TETRAY_SCALING_OUT:-out/scaling}
platforms=tools/composite_bench/platforms
mkdir -p "$out/hosts"

mpi_flags=(--oversubscribe --mca mpi_yield_when_idle 1)
[ "$(id -u)" -eq 0 ] && mpi_flags+=(--allow-run-as-root)

build_smpi() {
  if [ ! -f build-smpi/build.ninja ]; then
    cmake -S . -B build-smpi -G Ninja -DCMAKE_BUILD_TYPE=Release -DTETRAY_SMPI=ON \
      -DCMAKE_CXX_COMPILER=smpicxx -DTETRAY_WARNINGS_AS_ERRORS=ON >/dev/null
  fi
  cmake --build build-smpi >/dev/null
  [ -x build/bin/tetray-composite-bench ] || cmake --build build --target tetray-composite-bench
}

# hostfile NAME PREFIX NODES PER_NODE: every slot of the platform, ranks filling nodes in order.
hostfile() {
  local file=$out/hosts/$1.txt
  [ -f "$file" ] || python3 -c "
import sys
prefix, nodes, per = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
sys.stdout.write(''.join(f'{prefix}{n}\n' for n in range(nodes) for _ in range(per)))" \
    "$2" "$3" "$4" >"$file"
  echo "$file"
}

# The Blue Gene/P's ranks in Z-order of the torus (TETRAY_SCALING_MAPPING=zorder): consecutive
# ranks fill nodes along a Morton curve over x, y and z, so that every radix group (ranks 1, 8,
# 64, ... apart) lies in a compact block of nodes, a few links across; a job's mapping file
# (BG/P's BG_MAPPING) can place ranks so. The default fills nodes in the torus's own order (x
# fastest), as BG/P's default XYZT mapping does.
zorder_hostfile() {
  local file=$out/hosts/bluegene_p_zorder.txt
  [ -f "$file" ] || python3 -c "
dims = (8, 32, 32)
def key(c):
    k, bit = 0, 0
    for b in range(5):
        for a in range(3):
            if b < dims[a].bit_length() - 1:  # the coordinate's bits, interleaved
                k |= ((c[a] >> b) & 1) << bit
                bit += 1
    return k
nodes = sorted(((x, y, z) for x in range(8) for y in range(32) for z in range(32)), key=key)
print(''.join(f'bgp-{x + 8 * y + 256 * z}\n' * 4 for x, y, z in nodes), end='')" >"$file"
  echo "$file"
}

# The per-pixel costs of this machine's kernels (scan, encode, composite, copy, in ns), measured
# once by the normal build on 2 ranks, with TETRAY_SCALING_THREADS threads per rank (default 1;
# the ranks unbound, so that a rank's threads have the cores); the model images inject them.
costs() {
  local threads=${TETRAY_SCALING_THREADS:-1}
  local file=$out/costs_t$threads.json
  [ -f "$file" ] || mpirun -np 2 --bind-to none "${mpi_flags[@]}" build/bin/tetray-composite-bench \
    --sizes 64 --ranks 2 --repeat 1 --cost-size 2048 --threads "$threads" --json "$file" >/dev/null
  python3 -c "
import json, sys
c = json.load(open(sys.argv[1]))
print(' '.join(str(c[k]) for k in ('scan_ns_per_pixel', 'encode_ns_per_pixel',
                                   'composite_ns_per_pixel', 'copy_ns_per_pixel') if k in c))" "$file"
}

# simulate PLATFORM RANKS JSON [bench options]: one run of the simulator's bench.
# -no-privatize: the compositor and the bench keep no per-rank global state. Sends are never
# detached: SMPI keeps detached sends in a list that every later call scans, so that host time
# grows with the square of the ranks; the simulated sends become rendezvous, as MPI's large
# messages are. A model run with --byte-scale S divides the bandwidth by S (smpi/bw-factor, after
# the platform's own settings, which it overrides).
simulate() {
  local platform=$1 ranks=$2 json=$3
  shift 3
  local hosts
  case $platform in
    this_machine) hosts=$(hostfile this_machine here 1 32768) ;;
    cluster) hosts=$(hostfile cluster node- 4096 8) ;;
    bluegene_p)
      if [ "${TETRAY_SCALING_MAPPING:-torus}" = zorder ]; then
        hosts=$(zorder_hostfile)
      else
        hosts=$(hostfile bluegene_p bgp- 8192 4)
      fi ;;
    *) echo "unknown platform $platform" >&2; exit 2 ;;
  esac
  local settings=()
  while read -r line; do
    [[ -z $line || $line == \#* ]] || settings+=("--cfg=$line")
  done <"$platforms/$platform.cfg"
  local scale=1 args=("$@")
  for ((k = 0; k < ${#args[@]}; ++k)); do
    [ "${args[k]}" = --byte-scale ] && scale=${args[k + 1]}
  done
  [ "$scale" = 1 ] || settings+=("--cfg=smpi/bw-factor:0:$(python3 -c "print(1/$scale)")")
  # Simulated times repeat exactly: one run, unless asked (real images' computation is timed).
  local repeat=(--repeat 1)
  [[ " $* " == *" --repeat "* ]] && repeat=()
  # A model image's computation is injected: the host's time between MPI calls (its
  # bookkeeping, the allocation of its messages) must not count as well. Real images' does.
  [[ " $* " == *" --model "* ]] && settings+=(--cfg=smpi/simulate-computation:no)
  smpirun -no-privatize -np "$ranks" -hostfile "$hosts" -platform "$platforms/$platform.xml" \
    --cfg=smpi/host-speed:1Gf --cfg=smpi/send-is-detached-thresh:0 "${settings[@]}" \
    build-smpi/bin/tetray-composite-bench --ranks "$ranks" --json "$json" "${repeat[@]}" "$@" \
    2> >(grep -v '^\[' >&2)
}

calibrate() {
  local sizes=(1024 2048)
  for ranks in 2 4 8; do
    echo "== $ranks ranks: real mpirun, then the simulator of this machine"
    mpirun -np "$ranks" "${mpi_flags[@]}" build/bin/tetray-composite-bench --sizes "${sizes[@]}" \
      --ranks "$ranks" --repeat 5 --json "$out/real_$ranks.json" | tail -n +4
    simulate this_machine "$ranks" "$out/sim_$ranks.json" --sizes "${sizes[@]}" --repeat 5 |
      tail -n +4
  done
  scripts/scaling_report.py calibration "$out" >"$out/calibration.csv"
  column -s, -t <"$out/calibration.csv"
}

# The sweep: model images (their computation injected from this machine's per-pixel costs),
# every algorithm, the rows in the order the compositor picks (automatic), sparse images of
# 1024^2, 2048^2 and 8192^2 on both platforms, dense ones of 1024^2 and 2048^2 on the cluster (a
# dense 64-megapixel image is 1.6 GB on every rank). The
# plain gather to the root (P - 1 messages) only to 1,024 ranks. 1,000 and 3,000 ranks are not
# powers of two (radix-k takes both whole, 3,000 = 2^3 3 5^3; binary swap folds its extra ranks).
sweep() {
  local costs_ns
  costs_ns=$(costs)
  for platform in cluster bluegene_p; do
    for ranks in 16 64 256 1000 1024 3000 4096; do
      local algorithms=(binary_swap radix_k)
      ((ranks <= 1024)) && algorithms+=(gather)
      simulate "$platform" "$ranks" "$out/${platform}_${ranks}_sparse.json" --model \
        --costs-ns $costs_ns --coverage sparse --sizes 1024 2048 8192 --byte-scale 64 \
        --algorithms "${algorithms[@]}" >/dev/null
      if [ "$platform" = cluster ]; then
        simulate cluster "$ranks" "$out/cluster_${ranks}_dense.json" --model \
          --costs-ns $costs_ns --coverage dense --sizes 1024 2048 --byte-scale 64 \
          --algorithms "${algorithms[@]}" >/dev/null
      fi
      echo "$platform $ranks ranks: done ($SECONDS s)"
    done
  done
  scripts/scaling_report.py sweep "$out" >"$out/sweep.csv"
  scripts/scaling_report.py plot "$out"
}

# The Blue Gene/P table of docs/scaling.md: sparse 8192^2 images, radix-k, ranks in Z-order of
# the torus, the cube seen along z (sparse) and along x (sparse_x), rows natural and interlaced
# (natural only to 8,192 ranks: seen along z, its unbalanced rounds take the simulator hours
# past that). 32,768 simulated ranks need more memory maps than Linux's default 65,536 (two per
# rank): sysctl -w vm.max_map_count=262144.
bluegene() {
  local costs_ns
  costs_ns=$(costs)
  for ranks in 1024 4096 8192 16384 32768; do
    local maps=$((2 * ranks + 10000))
    if ((maps > $(cat /proc/sys/vm/max_map_count))); then
      echo "bluegene_p $ranks ranks: not run: needs vm.max_map_count of $maps or more" \
        "(sysctl -w vm.max_map_count=262144)" >&2
      continue
    fi
    local rows=(interlaced)
    ((ranks <= 8192)) && rows+=(natural)
    TETRAY_SCALING_MAPPING=zorder simulate bluegene_p "$ranks" \
      "$out/bluegene_p_zorder_${ranks}.json" --model --costs-ns $costs_ns \
      --coverage sparse sparse_x --sizes 8192 --byte-scale 64 --algorithms radix_k \
      --rows "${rows[@]}" >/dev/null
    echo "bluegene_p $ranks ranks: done ($SECONDS s)"
  done
  scripts/scaling_report.py rounds "$out" >"$out/bluegene_p_zorder.csv"
  column -s, -t <"$out/bluegene_p_zorder.csv"
}

case "${1:-}" in
  calibrate) build_smpi; calibrate ;;
  bluegene) build_smpi; bluegene ;;
  sweep) build_smpi; sweep ;;
  costs) [ -x build/bin/tetray-composite-bench ] || cmake --build build --target tetray-composite-bench
         costs ;;
  point) build_smpi; shift; platform=$1 ranks=$2; shift 2
         simulate "$platform" "$ranks" "$out/point.json" "$@" ;;
  *) sed -n '2,16p' "$0" >&2; exit 2 ;;
esac
