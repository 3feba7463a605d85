#!/usr/bin/env bash
# Builds Kokkos (Serial + OpenMP) from Debian's source package `trilinos` into a cache folder outside
# the build tree, and prints the install prefix on stdout. Reuses an existing install.
# Debian's binary Kokkos is serial-only, which is why we build it.
#
# The deb-src archive address is read from this machine's own apt sources at run time; a private
# sources list is passed with apt's -o options, so the machine's configuration is never modified.
set -euo pipefail
cache="${LSI_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/lsi}"
prefix="$cache/kokkos-openmp"
if [ -f "$prefix/.lsi-complete" ]; then echo "$prefix"; exit 0; fi
log() { echo "[kokkos] $*" >&2; }
work="$cache/kokkos-src"
src=$(bash "$(dirname "${BASH_SOURCE[0]}")/kokkos_source.sh" "$work")

# Configure standalone with Serial + OpenMP, build and install.
log "building Kokkos (Serial + OpenMP) into $prefix"
cmake -S "$src" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix" \
  -DKokkos_ENABLE_SERIAL=ON -DKokkos_ENABLE_OPENMP=ON -DKokkos_ENABLE_TESTS=OFF \
  -DBUILD_SHARED_LIBS=OFF -DCMAKE_POSITION_INDEPENDENT_CODE=ON -DCMAKE_CXX_STANDARD=17 \
  >"$work/build.log" 2>&1 || { tail -n 40 "$work/build.log" >&2; exit 1; }
{ cmake --build "$work/build" -j "$(nproc)" && cmake --install "$work/build"; } \
  >>"$work/build.log" 2>&1 || { tail -n 40 "$work/build.log" >&2; exit 1; }
touch "$prefix/.lsi-complete"
rm -rf "$work"
echo "$prefix"
