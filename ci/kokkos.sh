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
rm -rf "$work"; mkdir -p "$work/lists/partial" "$work/etc"

# 1. The Debian archive address of the configured bookworm 'main' sources (deb822 or one-line style).
uri=""
for f in /etc/apt/sources.list.d/*.sources; do
  [ -f "$f" ] || continue
  uri=$(awk 'BEGIN{RS="";FS="\n"} /Suites:[^\n]*bookworm( |\n|$)/ && /Components:[^\n]*main/ {
           for(i=1;i<=NF;i++) if ($i ~ /^URIs:/) {sub(/^URIs:[ \t]*/,"",$i); split($i,a," "); print a[1]; exit} }' "$f")
  [ -n "$uri" ] && break
done
if [ -z "$uri" ] && [ -f /etc/apt/sources.list ]; then
  uri=$(awk '$1=="deb" && / bookworm / && / main/ { for(i=2;i<=NF;i++) if ($i ~ /^[a-z]+:\/\//) {print $i; exit} }' /etc/apt/sources.list)
fi
[ -n "$uri" ] || { log "no Debian bookworm 'main' source found in /etc/apt; cannot fetch trilinos"; exit 1; }
keyring=/usr/share/keyrings/debian-archive-keyring.gpg
echo "deb-src [signed-by=$keyring] $uri bookworm main" > "$work/etc/sources.list"
opts=(-o "Dir::Etc::SourceList=$work/etc/sources.list" -o "Dir::Etc::SourceParts=/nonexistent"
      -o "Dir::State::Lists=$work/lists" -o "APT::Sandbox::User=root")

# 2. Download the source package (only the orig tarball is needed).
log "fetching trilinos source package"
apt-get "${opts[@]}" -qq update >&2
(cd "$work" && apt-get "${opts[@]}" -qq source --download-only trilinos >&2)
tarball=$(ls "$work"/trilinos_*.orig.tar.* | head -n 1)

# 3. Extract only packages/kokkos.
log "extracting packages/kokkos from $(basename "$tarball")"
mkdir -p "$work/src"
tar -xf "$tarball" -C "$work/src" --wildcards '*/packages/kokkos/*'
src=$(find "$work/src" -maxdepth 3 -type d -path '*/packages/kokkos' | head -n 1)

# 4. Configure standalone with Serial + OpenMP, build and install.
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
