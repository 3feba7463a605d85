#!/usr/bin/env bash
# Packs a CUDA build (ci/cuda_build.sh) to run on a GPU machine that has the NVIDIA driver but
# not the build's libraries or compilers: the test programs, lsi and the benchmarks (stripped),
# ctest's test lists, the shared libraries they load that are not the C and C++ runtimes (HDF5
# and its dependencies, Google Benchmark, the CUDA runtime), and CMake's GoogleTestAddTests.cmake,
# which ctest reads to list the tests when it runs. docs/guide/cuda.md, "Running a CUDA build elsewhere".
# usage: ci/cuda_bundle.sh OUT.tar.xz   (environment: LSI_CUDA_BUILD_DIR, default build-cuda/)
# LSI_CUDA_BUNDLE_ONLY="tests/mpm bench/bench_impact ...": only the programs under these paths of
# the build (a smaller bundle; without ctest's lists, which need every program: run it with
# `ci/cuda_bundle_test.sh BUNDLE --programs`).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:?usage: ci/cuda_bundle.sh OUT.tar.xz}")"
build="$(realpath "${LSI_CUDA_BUILD_DIR:-$root/build-cuda}")"
[ -f "$build/CMakeCache.txt" ] || { echo "[cuda-bundle] no build in $build" >&2; exit 1; }
stage="$(mktemp -d)"
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/build" "$stage/lib"
cd "$build"
# Executables (not the study programs, the MPI launcher or the fuzz replays: not run there).
only=()
for path in ${LSI_CUDA_BUNDLE_ONLY:-}; do only+=("./${path#./}"); done
mapfile -t programs < <(find "${only[@]:-.}" -type f -executable ! -name '*.so*' \
  ! -path '*/CMakeFiles/*' ! -name 'lsi-mpi' ! -name '*_study' ! -name 'fuzz_*')
for f in "${programs[@]}"; do
  mkdir -p "$stage/build/$(dirname "$f")"
  strip -o "$stage/build/$f" "$f"
done
if [ ${#only[@]} -eq 0 ]; then
  find . \( -name CTestTestfile.cmake -o -name '*_include*.cmake' -o -name '*_tests*.cmake' \) \
    ! -path '*/CMakeFiles/*' -exec cp --parents {} "$stage/build/" \;
fi
# The libraries the programs load, but the C/C++ runtimes that every Linux has.
for f in "${programs[@]}"; do ldd "$f"; done | awk '/=>/ {print $3}' | sort -u |
  grep -v -E '/(libc|libm|libdl|libpthread|librt|libresolv|libgcc_s|libstdc\+\+)\.so' |
  xargs -r -I{} cp -L {} "$stage/lib/"
module=$(grep -h -o '/[^"]*GoogleTestAddTests.cmake' -r . --include='*_include*.cmake' |
  head -n1 || true)
if [ -n "$module" ]; then cp "$module" "$stage/"; fi
printf '%s\n' "$build" > "$stage/BUILD_DIR"
sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' CMakeCache.txt > "$stage/SOURCE_DIR"
tar -C "$stage" -cf - . | xz -6 -T0 > "$out"
libraries=$(find "$stage/lib" -type f | wc -l)
echo "[cuda-bundle] $(du -h "$out" | cut -f1) in ${out}: ${#programs[@]} programs, $libraries libraries"
