#!/usr/bin/env bash
# Runs the tests of a bundle made by ci/cuda_bundle.sh on the GPU machine, from a checkout of the
# same revision (the tests read scenes from the source folder): unpacks it, puts the build and the
# source at the paths they were built with (symbolic links, where those paths are free), and runs
# ctest with the given arguments (default: the MPM, kernel and stability tests). Needs the NVIDIA
# driver and CMake's ctest. docs/guide/cuda.md, "Running a CUDA build elsewhere".
# usage: ci/cuda_bundle_test.sh BUNDLE.tar.xz [ctest arguments...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bundle="$(realpath "${1:?usage: ci/cuda_bundle_test.sh BUNDLE.tar.xz [ctest arguments...]}")"
shift
[ $# -gt 0 ] || set -- -L 'mpm|kernels|stability'
dir="$(mktemp -d)"
tar -C "$dir" -xJf "$bundle"
build="$(cat "$dir/BUILD_DIR")" source="$(cat "$dir/SOURCE_DIR")"
link() {   # link PATH TARGET: PATH -> TARGET unless PATH already is TARGET's content
  if [ "$(realpath -m "$1")" = "$(realpath "$2")" ]; then return; fi
  [ -e "$1" ] && { echo "[cuda-bundle] $1 exists: move it away first" >&2; exit 1; }
  mkdir -p "$(dirname "$1")" && ln -s "$2" "$1"
}
link "$build" "$dir/build"
link "$source" "$root"
if [ -f "$dir/GoogleTestAddTests.cmake" ]; then
  find "$dir/build/" -name '*_include*.cmake' -exec \
    sed -i "s#\"[^\"]*GoogleTestAddTests.cmake\"#\"$dir/GoogleTestAddTests.cmake\"#" {} +
fi
export LD_LIBRARY_PATH="$dir/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
cd "$build"
ctest --output-on-failure "$@"
