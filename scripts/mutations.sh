#!/usr/bin/env bash
# Mutation check of the test suite: each deliberate break listed in tests/mutations/mutations.txt
# (a file, its exact original text, a replacement, and the ctest regex of the tests that should
# notice) is applied in place, the executables of those tests are rebuilt incrementally in an
# already built build directory, those tests are run, and the file is restored (also on Ctrl-C or
# an error; a break left behind by a killed run is restored by the next run on the same build
# directory, which keeps the original in mutation-stash/). Prints one row per
# mutation: caught (some test failed) or SURVIVED, and the tests that failed. Exits non-zero if
# any mutation survived, did not apply or did not build. Not run in CI: it rebuilds once per
# mutation (docs/building.md, "Mutation check").
#   scripts/mutations.sh [-B build dir] [-j jobs] [--all] [--only id,id...] [--list]
#     -B DIR   the build directory, configured with the tests on and built (default: build)
#     -j N     jobs for the build and for ctest (default 1)
#     --all    build everything and run the whole suite for every mutation, not its regex
#     --only   only the mutations of these ids
#     --list   print the mutations and exit
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
list=tests/mutations/mutations.txt
build=build
jobs=1
all=0
only=""
while [ $# -gt 0 ]; do
  case "$1" in
    -B) build=$2; shift 2 ;;
    -j) jobs=$2; shift 2 ;;
    --all) all=1; shift ;;
    --only) only=",$2,"; shift 2 ;;
    --list) only=LIST; shift ;;
    -h | --help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
    *) echo "mutations.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
done
build=$(cd "$build" 2>/dev/null && pwd) || { echo "mutations.sh: no build directory '$build'" >&2; exit 2; }
if [ ! -f "$build/CTestTestfile.cmake" ] || [ ! -f "$build/build.ninja" ]; then
  echo "mutations.sh: $build is not a Ninja build with the tests on (cmake -G Ninja, TETRAY_BUILD_TESTS=ON)" >&2
  exit 2
fi

# One run per source tree: two would apply and restore the same files under each other (and the
# restore below would undo the other run's mutation).
exec 9>"${TMPDIR:-/tmp}/tetray-mutations-$(printf '%s' "$root" | md5sum | cut -c1-16).lock"
if ! flock -n 9; then
  echo "mutations.sh: another run is changing $root" >&2
  exit 2
fi

# While a mutation is applied its original file is kept here; restore() puts it back.
stash=$build/mutation-stash
restore() {
  [ -d "$stash" ] || return 0
  (cd "$stash" && find . -type f -print0) | while IFS= read -r -d '' f; do
    # A plain copy gives the file a new time stamp, so the next build recompiles what used it.
    cp "$stash/$f" "$root/$f"
    echo "mutations.sh: restored ${f#./}" >&2
  done
  rm -rf "$stash"
}
if [ -d "$stash" ]; then  # a run killed before its trap ran
  restore
  echo "mutations.sh: what that run built from the mutation stays until the next build" >&2
fi
trap restore EXIT
trap 'exit 130' INT TERM

# The mutations as tab-separated rows: id, file, from, to, tests. A block of "key: value" lines
# per mutation, blocks separated by blank lines, '#' lines ignored.
parse() {
  python3 - "$list" <<'EOF'
import sys
rows, block = [], {}
def flush():
    if not block:
        return
    missing = [k for k in ("id", "file", "from", "to", "tests") if k not in block]
    if missing:
        sys.exit(f"{sys.argv[1]}: mutation {block.get('id', '?')} lacks {', '.join(missing)}")
    rows.append("\t".join(block[k] for k in ("id", "file", "from", "to", "tests")))
    block.clear()
for line in open(sys.argv[1], encoding="utf-8"):
    line = line.rstrip("\n")
    if line.startswith("#"):
        continue
    if not line.strip():
        flush()
        continue
    key, sep, value = line.partition(":")
    if not sep or key.strip() not in ("id", "file", "from", "to", "tests", "why"):
        sys.exit(f"{sys.argv[1]}: cannot read line '{line}'")
    block[key.strip()] = value.strip()
flush()
print("\n".join(rows))
EOF
}

# Replaces the one occurrence of `from` in `file` by `to`; fails when it is not there once.
apply_mutation() {
  python3 - "$1" "$2" "$3" <<'EOF'
import sys
path, old, new = sys.argv[1:]
text = open(path, encoding="utf-8").read()
count = text.count(old)
if count != 1:
    sys.exit(f"the original text occurs {count} times in {path}")
open(path, "w", encoding="utf-8").write(text.replace(old, new))
EOF
}

# The build outputs that the tests matching regex $1 run (their executables), relative to $build,
# one a line; "-" alone when no test matches.
test_targets() {
  ctest --test-dir "$build" -N -R "$1" --show-only=json-v1 | python3 -c '
import json, os, subprocess, sys
build = sys.argv[1]
targets = subprocess.run(["ninja", "-C", build, "-t", "targets", "all"], capture_output=True,
                         text=True, check=True).stdout.splitlines()
outputs = {line.rsplit(":", 1)[0] for line in targets}
tests = json.load(sys.stdin).get("tests", [])
wanted = set()
for test in tests:
    for arg in test.get("command", []):
        path = os.path.relpath(arg.split("=", 1)[-1], build)
        if path in outputs:
            wanted.add(path)
print("\n".join(sorted(wanted)) if tests else "-")
' "$build"
}

rows=$(parse)
if [ "$only" = LIST ]; then
  printf '%s\n' "$rows" | awk -F'\t' '{printf "%-24s %-44s %s\n", $1, $2, $5}'
  exit 0
fi

log=$build/mutation-logs
mkdir -p "$log"
results=()
failures=0
built=()
while IFS=$'\t' read -r -u 3 id file from to tests; do
  [ -z "$only" ] || [[ "$only" == *",$id,"* ]] || continue
  regex=$tests
  [ "$all" = 1 ] && regex=.
  echo "== $id: $file" >&2
  mkdir -p "$stash/$(dirname "$file")"
  cp "$file" "$stash/$file"
  if ! apply_mutation "$file" "$from" "$to" 2>"$log/$id.apply"; then
    rm -rf "$stash"
    results+=("$id|NOT APPLIED|$(cat "$log/$id.apply")")
    failures=$((failures + 1))
    continue
  fi
  if [ "$all" = 1 ]; then
    targets=(all)
  else
    mapfile -t targets < <(test_targets "$regex" | sed "/^$/d")  # none: a script-only test
  fi
  if [ "${targets[*]}" = - ]; then
    restore
    results+=("$id|NO TESTS|no test matches '$regex'")
    failures=$((failures + 1))
    continue
  fi
  built+=("${targets[@]}")
  if [ ${#targets[@]} -gt 0 ] && ! ninja -C "$build" -j "$jobs" "${targets[@]}" >"$log/$id.build" 2>&1; then
    restore
    results+=("$id|BUILD FAILED|see $log/$id.build")
    failures=$((failures + 1))
    continue
  fi
  rm -f "$build/Testing/Temporary/LastTestsFailed.log"
  if ctest --test-dir "$build" -R "$regex" -j "$jobs" --timeout 600 --output-on-failure >"$log/$id.test" 2>&1; then
    results+=("$id|SURVIVED|no test of '$regex' failed")
    failures=$((failures + 1))
  else
    failed=$(sed 's/^[0-9]*://' "$build/Testing/Temporary/LastTestsFailed.log" 2>/dev/null |
      paste -sd' ' -)
    results+=("$id|caught|${failed:-ctest failed, see $log/$id.test}")
  fi
  restore
done 3<<<"$rows"

# Leave no mutated object behind: rebuild what was built, on the restored sources.
if [ ${#built[@]} -gt 0 ]; then
  mapfile -t built < <(printf '%s\n' "${built[@]}" | sort -u)
  echo "== rebuilding ${#built[@]} targets on the restored sources" >&2
  ninja -C "$build" -j "$jobs" "${built[@]}" >"$log/restored.build" 2>&1 ||
    echo "mutations.sh: the rebuild on the restored sources failed, see $log/restored.build" >&2
fi

printf '\n%-24s %-12s %s\n' mutation result "failing tests"
for row in "${results[@]}"; do
  IFS='|' read -r id result detail <<<"$row"
  printf '%-24s %-12s %s\n' "$id" "$result" "$detail"
done
[ "$failures" -eq 0 ]
