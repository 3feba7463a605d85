#!/usr/bin/env bash
# README command 2: installs what is missing, builds, and runs every test.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/ci/setup.sh"
build="${LSI_BUILD_DIR:-$root/build}"
OMP_PROC_BIND=false ctest --test-dir "$build" --output-on-failure -j "$(nproc)"
