#!/usr/bin/env bash
# Builds Kokkos with the CUDA backend (and Serial + OpenMP for the host) from the same Debian
# `trilinos` source as ci/kokkos.sh, into a cache folder outside the build tree; prints the install
# prefix on stdout. Reuses an existing install. No GPU is needed to build, only nvcc:
#
#   prefix=$(LSI_CUDA_ARCH=HOPPER90 bash ci/kokkos_cuda.sh)
#   cmake -S . -B build-cuda -DKokkos_ROOT=$prefix -DLSI_NATIVE_ARCH=OFF     # docs/guide/cuda.md
#
# Environment: LSI_CUDA_ARCH (a Kokkos architecture: VOLTA70, TURING75, AMPERE80, AMPERE86 or
# HOPPER90; default HOPPER90), CUDA_HOME (default /usr/local/cuda), LSI_CACHE (as ci/kokkos.sh).
#
# Debian's Kokkos is 3.4.1, older than CUDA 12 and the Hopper GPUs. Five small changes to the
# extracted copy (never to anything installed) make it build with CUDA 12/13 and run on an H100;
# each is checked to apply, and docs/guide/cuda.md says why each is needed.
set -euo pipefail
cache="${LSI_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/lsi}"
arch="${LSI_CUDA_ARCH:-HOPPER90}"
case "$arch" in
  VOLTA70) sm=sm_70 ;; TURING75) sm=sm_75 ;; AMPERE80) sm=sm_80 ;; AMPERE86) sm=sm_86 ;;
  HOPPER90) sm=sm_90 ;;
  *) echo "[kokkos-cuda] LSI_CUDA_ARCH=$arch: expected one of VOLTA70 TURING75 AMPERE80 AMPERE86 HOPPER90" >&2; exit 2 ;;
esac
# Position-independent code (as ci/kokkos.sh), so that the Python module, a shared object, links
# the static libraries; "-pic" keeps an older install without it from being reused.
prefix="$cache/kokkos-cuda-$arch-pic"
if [ -f "$prefix/.lsi-complete" ]; then echo "$prefix"; exit 0; fi
log() { echo "[kokkos-cuda] $*" >&2; }
cuda="${CUDA_HOME:-/usr/local/cuda}"
command -v nvcc >/dev/null || export PATH="$cuda/bin:$PATH"
command -v nvcc >/dev/null || { log "nvcc not found (set CUDA_HOME or put nvcc on PATH)"; exit 1; }
work="$cache/kokkos-cuda-src"
src=$(bash "$(dirname "${BASH_SOURCE[0]}")/kokkos_source.sh" "$work")

# patch FILE: replaces the text of $old by $new in FILE exactly once, or fails naming the file.
patch_once() {
  OLD="$old" NEW="$new" python3 - "$1" <<'PY' || { log "patch did not apply to $1"; exit 1; }
import os, sys
path = sys.argv[1]
text = open(path).read()
old, new = os.environ["OLD"], os.environ["NEW"]
if text.count(old) != 1:
    sys.exit(1)
open(path, "w").write(text.replace(old, new))
PY
}
version=$(sed -n 's/^set(Kokkos_VERSION_\(MAJOR\|MINOR\|PATCH\) \([0-9]*\))/\2/p' "$src/CMakeLists.txt" | paste -sd.)
log "adapting Kokkos $version to CUDA $(nvcc --version | sed -n 's/.*release \([0-9.]*\).*/\1/p') and $arch"
# 1. The Hopper architecture (compute capability 9.0), unknown to Kokkos 3.4.
old='KOKKOS_ARCH_OPTION(AMPERE86        GPU  "NVIDIA Ampere generation CC 8.6")'
new="$old"$'\nKOKKOS_ARCH_OPTION(HOPPER90        GPU  "NVIDIA Hopper generation CC 9.0")'
patch_once "$src/cmake/kokkos_arch.cmake"
old='CHECK_CUDA_ARCH(AMPERE86  sm_86)'
new="$old"$'\nCHECK_CUDA_ARCH(HOPPER90  sm_90)'
patch_once "$src/cmake/kokkos_arch.cmake"
old='#cmakedefine KOKKOS_ARCH_AMPERE86'
new="$old"$'\n#cmakedefine KOKKOS_ARCH_HOPPER90'
patch_once "$src/cmake/KokkosCore_config.h.in"
# 2. nvcc_wrapper: hand -std=c++20 to nvcc as well (3.4 gives it to the host compiler only, so the
#    device pass would parse lsi's C++20 as C++17), and a default architecture that CUDA 12 still
#    has (sm_35 is gone; used only by CMake's compiler check).
old='  --std=c++17|-std=c++17)'
new='  --std=c++17|-std=c++17|--std=c++20|-std=c++20)'
patch_once "$src/bin/nvcc_wrapper"
old='default_arch="sm_35"'
new="default_arch=\"$sm\""
patch_once "$src/bin/nvcc_wrapper"
# 3. No CUDA half_t: 3.4's wrapper of __half does not compile against CUDA 13's cuda_fp16.h; Kokkos
#    then defines half_t as float (lsi uses no half precision).
old='#if !(defined(KOKKOS_COMPILER_CLANG) && KOKKOS_COMPILER_CLANG < 900) && \'
new='#if defined(KOKKOS_IMPL_ENABLE_CUDA_HALF) && !(defined(KOKKOS_COMPILER_CLANG) && KOKKOS_COMPILER_CLANG < 900) && \'
patch_once "$src/core/src/Cuda/Kokkos_Cuda_Half.hpp"
# 4. CUDA 13 replaced cudaMemPrefetchAsync's device number by a cudaMemLocation and a flags word.
old='    CUDA_SAFE_CALL(cudaMemPrefetchAsync(ptr, bytes, space.cuda_device(),
                                        space.cuda_stream()));'
new='#if CUDART_VERSION >= 13000
    cudaMemLocation location{};
    location.type = cudaMemLocationTypeDevice;
    location.id   = space.cuda_device();
    CUDA_SAFE_CALL(
        cudaMemPrefetchAsync(ptr, bytes, location, 0, space.cuda_stream()));
#else
'"$old"'
#endif'
patch_once "$src/core/src/Cuda/Kokkos_CudaSpace.cpp"

log "building Kokkos (CUDA $arch + Serial + OpenMP) into $prefix"
cmake -S "$src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix" \
  -DCMAKE_CXX_COMPILER="$src/bin/nvcc_wrapper" -DCMAKE_CXX_STANDARD=17 \
  -DKokkos_ENABLE_SERIAL=ON -DKokkos_ENABLE_OPENMP=ON -DKokkos_ENABLE_CUDA=ON \
  -DKokkos_ENABLE_CUDA_LAMBDA=ON "-DKokkos_ARCH_$arch=ON" -DKokkos_ENABLE_TESTS=OFF \
  -DBUILD_SHARED_LIBS=OFF -DCMAKE_POSITION_INDEPENDENT_CODE=ON >"$work/build.log" 2>&1 || { tail -n 40 "$work/build.log" >&2; exit 1; }
{ cmake --build "$work/build" -j "$(nproc)" && cmake --install "$work/build"; } \
  >>"$work/build.log" 2>&1 || { tail -n 40 "$work/build.log" >&2; exit 1; }
touch "$prefix/.lsi-complete"
rm -rf "$work"
echo "$prefix"
