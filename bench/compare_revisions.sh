#!/usr/bin/env bash
# Compare a benchmark between two git revisions of this repository.
#
#   bench/compare_revisions.sh REV_A REV_B [BENCH] [FILTER]
#
# REV_A (old) and REV_B (new): anything `git rev-parse` takes (HEAD~1, a branch, a hash);
# BENCH: a benchmark program of bench/ (default bench_mpm); FILTER: its --benchmark_filter
# (default: all its benchmarks). Each revision is checked out with `git worktree add --detach`
# into a temporary directory (your own checkout, branch and index are not touched), configured in
# Release without the tests, and only BENCH is built; then the two binaries run with
#   --benchmark_filter=FILTER --benchmark_repetitions=$REPETITIONS
#   --benchmark_out=<rev>.json --benchmark_out_format=json
# and the two JSON files are compared: with Google Benchmark's tools/compare.py when COMPARE_PY
# names it (`$COMPARE_PY benchmarks A.json B.json`, which adds a Mann-Whitney U test), else with
# bench/compare_json.py (median per benchmark on each side and the ratio B / A).
#
# Environment:
#   REPETITIONS=5     --benchmark_repetitions of each run
#   ROUNDS=1          run A, B, A, B, ... ROUNDS times each, merged into one JSON per side: on a
#                     machine whose speed drifts (docs/notes/performance.md) both binaries then see the
#                     same drift; e.g. ROUNDS=5 REPETITIONS=1
#   METRIC=real_time  what compare_json.py compares (cpu_time, items_per_second, a counter...)
#   OUT_DIR           where the JSON files go (default: a new directory under /tmp, printed)
#   JOBS=2            parallel compile jobs
#   Kokkos_ROOT       your Kokkos install (else the repository's cached OpenMP build, ci/kokkos.sh)
#   CMAKE_ARGS        further configure arguments, e.g. "-DLSI_NATIVE_ARCH=OFF"
#   COMPARE_PY        path of Google Benchmark's tools/compare.py (needs numpy and scipy)
#   KEEP=1            keep the worktrees and build directories (printed) instead of removing them
#   OMP_NUM_THREADS, OMP_PROC_BIND (default false), OMP_WAIT_POLICY (default passive): passed on.
#
# Example (the grid update kernel, 5 alternating rounds of 1 repetition, 2 threads):
#   ROUNDS=5 REPETITIONS=1 OMP_NUM_THREADS=2 bench/compare_revisions.sh HEAD~1 HEAD bench_mpm \
#       '^kernel/OpenMP/grid_update/particles:20000/'
set -euo pipefail

if [[ $# -lt 2 || $# -gt 4 ]]; then
  sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
  exit 2
fi
rev_a=$1
rev_b=$2
bench=${3:-bench_mpm}
filter=${4:-.}
repetitions=${REPETITIONS:-5}
rounds=${ROUNDS:-1}
metric=${METRIC:-real_time}
jobs=${JOBS:-2}
export OMP_PROC_BIND=${OMP_PROC_BIND:-false}
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(git -C "$here" rev-parse --show-toplevel)
compare_json=$here/compare_json.py
python=/usr/bin/python3
[[ -x $python ]] || python=python3

hash_a=$(git -C "$repo" rev-parse --verify --quiet "$rev_a^{commit}") ||
  { echo "compare_revisions: not a commit: $rev_a" >&2; exit 2; }
hash_b=$(git -C "$repo" rev-parse --verify --quiet "$rev_b^{commit}") ||
  { echo "compare_revisions: not a commit: $rev_b" >&2; exit 2; }
short_a=$(git -C "$repo" rev-parse --short=12 "$hash_a")
short_b=$(git -C "$repo" rev-parse --short=12 "$hash_b")

work=$(mktemp -d /tmp/lsi-compare.XXXXXX)
out_dir=${OUT_DIR:-$work/results}
mkdir -p "$out_dir"
out_dir=$(cd "$out_dir" && pwd)
worktrees=()
cleanup() {
  if [[ ${KEEP:-0} == 1 ]]; then
    echo "compare_revisions: kept the worktrees and builds under $work" >&2
    return
  fi
  for w in "${worktrees[@]}"; do
    git -C "$repo" worktree remove --force "$w" >/dev/null 2>&1 ||
      echo "compare_revisions: could not remove the worktree $w (git worktree remove)" >&2
  done
  # The results stay (they are the point); the sources and builds go.
  if [[ $out_dir == "$work"/* ]]; then
    find "$work" -mindepth 1 -maxdepth 1 ! -name results -exec rm -rf {} +
  else
    rm -rf "$work"
  fi
}
trap cleanup EXIT

cmake_args=(-DCMAKE_BUILD_TYPE=Release -DLSI_BUILD_TESTS=OFF -DLSI_BUILD_BENCH=ON)
if [[ -n ${Kokkos_ROOT:-} ]]; then
  cmake_args+=("-DKokkos_ROOT=$Kokkos_ROOT")
fi
# shellcheck disable=SC2206
cmake_args+=(${CMAKE_ARGS:-})

built=""
build() {   # build LABEL HASH -> sets $built to the binary's path (no subshell: the worktree
            # must reach the list that cleanup removes)
  local label=$1 hash=$2 src=$work/src-$1 bld=$work/build-$1
  echo "compare_revisions: $label = $(git -C "$repo" log -1 --format='%h %s' "$hash")" >&2
  git -C "$repo" worktree add --detach "$src" "$hash" >/dev/null 2>&1 ||
    { echo "compare_revisions: git worktree add failed for $hash" >&2; exit 1; }
  worktrees+=("$src")
  if [[ ! -f $src/bench/$bench.cpp ]]; then
    echo "compare_revisions: $label ($hash) has no bench/$bench.cpp" >&2
    exit 1
  fi
  cmake -S "$src" -B "$bld" "${cmake_args[@]}" >"$work/configure-$label.log" 2>&1 ||
    { tail -20 "$work/configure-$label.log" >&2; exit 1; }
  cmake --build "$bld" --target "$bench" -j "$jobs" >"$work/build-$label.log" 2>&1 ||
    { tail -40 "$work/build-$label.log" >&2; exit 1; }
  built=$bld/bench/$bench
}

start=$(date +%s)
build A "$hash_a"
bin_a=$built
build B "$hash_b"
bin_b=$built
echo "compare_revisions: built both in $(($(date +%s) - start)) s" >&2

run() {   # run BINARY OUT.json
  "$1" --benchmark_filter="$filter" --benchmark_repetitions="$repetitions" \
    --benchmark_out="$2" --benchmark_out_format=json >/dev/null 2>"$2.log" ||
    { tail -20 "$2.log" >&2; exit 1; }
  "$python" -c 'import json, sys; sys.exit(0 if json.load(open(sys.argv[1])).get("benchmarks") else 1)' \
    "$2" 2>/dev/null ||
    { tail -5 "$2.log" >&2
      echo "compare_revisions: no benchmark of $bench matched '$filter' (see: $bench --benchmark_list_tests)" >&2
      exit 1; }
  rm -f "$2.log"
}

json_a=$out_dir/$bench-$short_a.json
json_b=$out_dir/$bench-$short_b.json
[[ $short_a == "$short_b" ]] && json_b=$out_dir/$bench-$short_b-B.json
if [[ $rounds -le 1 ]]; then
  echo "compare_revisions: running A ($repetitions repetitions, load $(cut -d' ' -f1-3 /proc/loadavg))" >&2
  run "$bin_a" "$json_a"
  echo "compare_revisions: running B ($repetitions repetitions, load $(cut -d' ' -f1-3 /proc/loadavg))" >&2
  run "$bin_b" "$json_b"
else
  parts_a=() parts_b=()
  for ((r = 1; r <= rounds; ++r)); do
    echo "compare_revisions: round $r of $rounds (load $(cut -d' ' -f1-3 /proc/loadavg))" >&2
    run "$bin_a" "$work/a-$r.json"
    parts_a+=("$work/a-$r.json")
    run "$bin_b" "$work/b-$r.json"
    parts_b+=("$work/b-$r.json")
  done
  "$python" "$compare_json" merge "$json_a" "${parts_a[@]}"
  "$python" "$compare_json" merge "$json_b" "${parts_b[@]}"
fi
echo "compare_revisions: results in $json_a and $json_b" >&2
echo
if [[ -n ${COMPARE_PY:-} ]]; then
  "$python" "$COMPARE_PY" benchmarks "$json_a" "$json_b"
else
  "$python" "$compare_json" --metric "$metric" "$json_a" "$json_b"
fi
