#!/usr/bin/env bash
# Runs the tests of a bundle made by ci/cuda_bundle.sh on the GPU machine, from a checkout of the
# same revision (the tests read scenes from the source folder): unpacks it, puts the build and the
# source at the paths they were built with (symbolic links, where those paths are free), and runs
# ctest with the given arguments (default: the MPM, kernel and stability tests). Needs the NVIDIA
# driver and CMake's ctest. docs/guide/cuda.md, "Running a CUDA build elsewhere".
# usage: ci/cuda_bundle_test.sh BUNDLE.tar.xz [ctest arguments...]
#        ci/cuda_bundle_test.sh BUNDLE.tar.xz --programs
# --programs (a bundle of some programs, LSI_CUDA_BUNDLE_ONLY, which ctest cannot list): runs
# every test program of the bundle itself, 8 at once with 2 OpenMP threads each (logs in
# LSI_LOG_DIR, default a temporary folder), names those that failed, then the campaign benchmark
# (bench_impact --benchmark_filter=^campaign/, with every CPU) when the bundle has it.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bundle="$(realpath "${1:?usage: ci/cuda_bundle_test.sh BUNDLE.tar.xz [ctest arguments...]}")"
shift
[ $# -gt 0 ] || set -- -L 'mpm|kernels|stability'
dir="$(mktemp -d)"
tar -C "$dir" -xJf "$bundle"
build="$(cat "$dir/BUILD_DIR")" source="$(cat "$dir/SOURCE_DIR")"
link() {   # link PATH TARGET: PATH -> TARGET unless PATH already is TARGET's content
  if [ "$(realpath -m "$1")" = "$(realpath "$2")" ]; then return; fi
  [ -e "$1" ] && { echo "[cuda-bundle] $1 exists: move it away first" >&2; exit 1; }
  mkdir -p "$(dirname "$1")" && ln -s "$2" "$1"
}
link "$build" "$dir/build"
link "$source" "$root"
if [ -f "$dir/GoogleTestAddTests.cmake" ]; then
  find "$dir/build/" -name '*_include*.cmake' -exec \
    sed -i "s#\"[^\"]*GoogleTestAddTests.cmake\"#\"$dir/GoogleTestAddTests.cmake\"#" {} +
fi
export LD_LIBRARY_PATH="$dir/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
cd "$build"
if [ "$1" != --programs ]; then
  ctest --output-on-failure "$@"
  exit
fi
export OMP_PROC_BIND=false OMP_WAIT_POLICY=passive
logs="${LSI_LOG_DIR:-$dir/logs}"
mkdir -p "$logs"
status=0
find tests -type f -executable | sort |
  OMP_NUM_THREADS=2 xargs -P 8 -I{} sh -c \
    'timeout 600 {} --gtest_brief=1 > "$0/$(basename {}).log" 2>&1 || echo "{}"' "$logs" \
    > "$logs/failed.txt"
if [ -s "$logs/failed.txt" ]; then
  status=1
  echo "[cuda-bundle] failed (logs in $logs):" >&2
  cat "$logs/failed.txt" >&2
  grep -h "^\[  FAILED  \]" "$logs"/*.log | sort -u >&2 || true
else
  echo "[cuda-bundle] every test program passed (logs in $logs)"
fi
if [ -x bench/bench_impact ]; then
  OMP_NUM_THREADS=$(nproc) bench/bench_impact --benchmark_filter='^campaign/' \
    --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
    --benchmark_out="$logs/campaign.json" --benchmark_out_format=json
fi
exit "$status"
