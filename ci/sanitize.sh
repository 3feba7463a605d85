#!/usr/bin/env bash
# The whole test suite under AddressSanitizer and UndefinedBehaviorSanitizer (issue 6): configures
# the `sanitize` preset of CMakePresets.json into build-sanitize/ (-O1 -g, every lsi target built
# with -fsanitize=address,undefined, any finding fatal), builds it, and runs every test with the
# environment of the `sanitize` test preset (leak checking on, suppressions in ci/sanitize/lsan.supp).
# Run before each release; takes about 4 times the normal suite (docs/vv/robustness.md).
# usage: ci/sanitize.sh [ctest arguments, e.g. -L mpm or -R Sweep]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
LSI_PRESET=sanitize LSI_BUILD_DIR="$root/build-sanitize" bash "$root/ci/setup.sh"
cd "$root"
ctest --preset sanitize -j "$(nproc)" "$@"
