#!/usr/bin/env bash
# Installs what is missing (Debian packages, Kokkos with OpenMP), configures and builds lsi into build/.
# Idempotent: a second run installs nothing and rebuilds only what changed.
# Environment: LSI_BUILD_DIR (default build), LSI_BUILD_TYPE (default Release),
#              Kokkos_ROOT (use your own Kokkos, e.g. with CUDA; nothing is built then),
#              LSI_PRESET (configure with a preset of CMakePresets.json, e.g. sanitize).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${LSI_BUILD_DIR:-$root/build}"
# libopenmpi-dev openmpi-bin: OpenMPI from Debian, as the issue asks, for lsi-mpi (docs/guide/mpi.md).
# clang-format: the style check of the tests (ci/format_check.sh, .clang-format).
# python3-openturns: the test of tools/openturns_wrapper.py (lsi as an OpenTURNS function).
# pybind11-dev python3-dev python3-numpy python3-pytest: the Python module lsi (python/,
# docs/guide/python.md): pybind11 and Python's headers build it, NumPy holds its arrays, pytest
# runs its test.
packages=(g++ cmake make libeigen3-dev libbenchmark-dev libgtest-dev libhdf5-dev libcli11-dev
          nlohmann-json3-dev python3-matplotlib python3-h5py libopenmpi-dev openmpi-bin
          clang-format python3-openturns pybind11-dev python3-dev python3-numpy python3-pytest)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[setup] installing Debian packages: ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then sudo=sudo; else sudo=; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
cmake_args=(-DCMAKE_BUILD_TYPE="${LSI_BUILD_TYPE:-Release}")
[ -n "${Kokkos_ROOT:-}" ] && cmake_args+=(-DKokkos_ROOT="$Kokkos_ROOT")
[ -n "${LSI_PRESET:-}" ] && cmake_args=(--preset "$LSI_PRESET" "${cmake_args[@]:1}")
if [ ! -f "$build/CMakeCache.txt" ]; then
  cmake -S "$root" -B "$build" "${cmake_args[@]}" >/dev/null
fi
cmake --build "$build" -j "$(nproc)" 2>&1 | grep -E 'error|warning|Error' || true
cmake --build "$build" -j "$(nproc)" >/dev/null   # fails (set -e) if the build is broken
echo "[setup] built lsi in $build"
