#!/usr/bin/env bash
# Fetches Debian's source package `trilinos` and extracts its packages/kokkos folder into the work
# folder given as the first argument (emptied first); prints the path of that Kokkos source on
# stdout. Used by ci/kokkos.sh (OpenMP) and ci/kokkos_cuda.sh (CUDA).
#
# The deb-src archive address is read from this machine's own apt sources at run time; a private
# sources list is passed with apt's -o options, so the machine's configuration is never modified.
set -euo pipefail
work="${1:?usage: kokkos_source.sh WORK_DIR}"
log() { echo "[kokkos] $*" >&2; }
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
rm -f "$tarball"
find "$work/src" -maxdepth 3 -type d -path '*/packages/kokkos' | head -n 1
