#!/usr/bin/env bash
# The long fuzz campaign of the scene and study parsers (docs/vv/robustness.md, "Fuzzing"):
# libFuzzer with AddressSanitizer and UndefinedBehaviorSanitizer, Debian's clang.
#
#   bash ci/fuzz.sh [SECONDS] [TARGET...]    SECONDS per target (default 300); TARGET: scene, study
#
# It configures its own build directory with clang and -DLSI_FUZZ_LIBFUZZER=ON and builds only
# the fuzz targets (the parser sources, instrumented; tests/fuzz/CMakeLists.txt). For each target
# it then
#   1. runs the standalone driver under the sanitizers: the seed corpus, every input of
#      tests/fuzz/regressions/TARGET (each crash ever found must stay fixed) and the same
#      deterministic mutants as the `fuzz` ctest tests;
#   2. fuzzes for SECONDS with libFuzzer from the seed corpus (the shipped scenes/ and studies,
#      tests/fuzz/corpus/) with the dictionary tests/fuzz/lsi.dict and the JSON-aware custom
#      mutator. The corpus grown by libFuzzer is kept in the build directory for the next run.
# Any crash, leak, timeout or out-of-memory input is copied to tests/fuzz/regressions/TARGET/ and
# the script exits 1: fix the parser, keep the input (the `fuzz` ctest tests replay it in every
# build) and note it in docs/vv/robustness.md.
#
# Environment: LSI_FUZZ_BUILD_DIR (default build-fuzz), LSI_FUZZ_JOBS (build jobs, default 2),
#              Kokkos_ROOT (as for ci/setup.sh; default: the cached build of ci/kokkos.sh).
# Needs Debian's clang, libclang-rt-dev (libFuzzer, sanitizers) and libomp-dev (the OpenMP runtime
# for the GCC-built Kokkos's calls), installed here when missing, and the packages of ci/setup.sh.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-300}"
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(scene study)
build="${LSI_FUZZ_BUILD_DIR:-$root/build-fuzz}"
case "$seconds" in '' | *[!0-9]*) echo "ci/fuzz.sh: SECONDS must be a whole number, got '$seconds'" >&2; exit 2 ;; esac

missing=()
for p in clang libclang-rt-dev libomp-dev; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[fuzz] installing Debian packages: ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then sudo=sudo; else sudo=; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake_args=(-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo
              -DLSI_FUZZ_LIBFUZZER=ON -DLSI_BUILD_BENCH=OFF)
  [ -n "${Kokkos_ROOT:-}" ] && cmake_args+=(-DKokkos_ROOT="$Kokkos_ROOT")
  cmake -S "$root" -B "$build" "${cmake_args[@]}" >/dev/null
fi
executables=()
for t in "${targets[@]}"; do executables+=("fuzz_$t" "fuzz_${t}_replay"); done
cmake --build "$build" -j "${LSI_FUZZ_JOBS:-2}" --target "${executables[@]}" >/dev/null
echo "[fuzz] built ${executables[*]} in $build"

# One process per target, Kokkos on one thread: the parsers are serial, and the machine may be small.
export OMP_NUM_THREADS=1 OMP_PROC_BIND=false
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_stack_use_after_return=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
found=0
for t in "${targets[@]}"; do
  exe="$build/tests/fuzz/fuzz_$t"
  regressions="$root/tests/fuzz/regressions/$t"
  corpus="$build/fuzz-corpus/$t"
  artifacts="$build/fuzz-artifacts/$t"
  mkdir -p "$corpus" "$artifacts" "$regressions"
  # The seeds and mutant counts of the ctest tests (tests/fuzz/CMakeLists.txt).
  case "$t" in
    scene) seeds=("$root/scenes/reference" "$root/scenes/examples" "$root/scenes/verification" "$root/tests/fuzz/corpus/scene")
           mutants=20000 ;;
    study) seeds=("$root/scenes/studies" "$root/tests/fuzz/corpus/study")
           mutants=6000 ;;
    *) echo "ci/fuzz.sh: unknown target '$t' (scene, study)" >&2; exit 2 ;;
  esac

  echo "[fuzz] $t: replaying the corpus, the regressions and $mutants mutants under the sanitizers"
  replay_inputs=("${seeds[@]}")
  [ -n "$(find "$regressions" -type f ! -name '.*' -print -quit)" ] && replay_inputs+=("$regressions")
  rm -f "$artifacts/fuzz_${t}_replay-crash.json"
  if ! (cd "$artifacts" && ASAN_OPTIONS="$ASAN_OPTIONS:abort_on_error=1" \
        UBSAN_OPTIONS="$UBSAN_OPTIONS:abort_on_error=1" \
        "$build/tests/fuzz/fuzz_${t}_replay" --mutants "$mutants" --seed 1 "${replay_inputs[@]}") \
        > "$artifacts/replay.log" 2>&1; then
    grep -m 5 -E 'ERROR|lsi fuzz|runtime error|SUMMARY' "$artifacts/replay.log" || tail -n 20 "$artifacts/replay.log"
    if [ -f "$artifacts/fuzz_${t}_replay-crash.json" ]; then
      name="replay-$(sha1sum "$artifacts/fuzz_${t}_replay-crash.json" | cut -c1-40).json"
      cp "$artifacts/fuzz_${t}_replay-crash.json" "$regressions/$name"
      echo "[fuzz] $t: new regression input tests/fuzz/regressions/$t/$name"
    fi
    found=1
    continue
  fi
  tail -n 1 "$artifacts/replay.log"

  echo "[fuzz] $t: fuzzing for $seconds s (log: $artifacts/fuzz.log)"
  set +e
  "$exe" "$corpus" "${seeds[@]}" "$regressions" -dict="$root/tests/fuzz/lsi.dict" -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -max_len=16384 -print_final_stats=1 \
    -artifact_prefix="$artifacts/" > "$artifacts/fuzz.log" 2>&1
  rc=$?
  set -e
  grep -E '^(#[0-9]+ *DONE|stat::number_of_executed_units|stat::average_exec_per_sec|stat::new_units_added|stat::peak_rss_mb)' "$artifacts/fuzz.log" || true
  shopt -s nullglob
  crashes=("$artifacts"/crash-* "$artifacts"/leak-* "$artifacts"/timeout-* "$artifacts"/oom-*)
  shopt -u nullglob
  if [ ${#crashes[@]} -gt 0 ] || [ $rc -ne 0 ]; then
    found=1
    grep -m 5 -E 'ERROR|lsi fuzz:|runtime error|SUMMARY' "$artifacts/fuzz.log" || true
    for c in "${crashes[@]}"; do
      cp "$c" "$regressions/"
      echo "[fuzz] $t: new regression input tests/fuzz/regressions/$t/$(basename "$c")"
      rm "$c"
    done
    [ ${#crashes[@]} -eq 0 ] && echo "[fuzz] $t: libFuzzer exited with $rc without an artifact; see $artifacts/fuzz.log"
  fi
done
[ $found -eq 0 ] && echo "[fuzz] no crash found"
exit $found
