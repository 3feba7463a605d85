#!/usr/bin/env bash
# Compiles the whole tree (kernels, driver, tests, benchmarks) for the CUDA backend: the check that
# the device code still compiles, for a machine with nvcc and no GPU (docs/guide/cuda.md). Builds or
# reuses the CUDA Kokkos of ci/kokkos_cuda.sh, configures build-cuda/ (or LSI_CUDA_BUILD_DIR)
# without host-specific vector instructions, and builds every target, going on past a failing one
# so that one run lists every file nvcc rejects. About 12 minutes on 2 cores from scratch.
# Running the result needs the GPU: ctest --test-dir build-cuda -L 'mpm|kernels|stability'.
# usage: ci/cuda_build.sh   (environment: LSI_CUDA_ARCH, CUDA_HOME as ci/kokkos_cuda.sh)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
command -v nvcc >/dev/null || export PATH="${CUDA_HOME:-/usr/local/cuda}/bin:$PATH"
prefix=$(bash "$root/ci/kokkos_cuda.sh")
build="${LSI_CUDA_BUILD_DIR:-$root/build-cuda}"
cmake -S "$root" -B "$build" -DKokkos_ROOT="$prefix" -DLSI_NATIVE_ARCH=OFF \
  -DCMAKE_BUILD_TYPE=Release >/dev/null
status=0
cmake --build "$build" -j "$(nproc)" -- -k || status=$?
if [ "$status" -ne 0 ]; then
  echo "[cuda-build] some targets did not compile for CUDA (errors above)" >&2
  exit "$status"
fi
echo "[cuda-build] every target compiled for CUDA into ${build#$root/}/"
