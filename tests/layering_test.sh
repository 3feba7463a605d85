#!/usr/bin/env bash
# The rooms of the code depend one way (docs/reference/architecture.md): kernels/ and sweeps/ on nothing of
# lsi's above them, model/ on those, io/ on model/, app/ and python/ (the Python module) beside
# each other on io/ and model/. Fails, naming the file and the line, for an #include that runs
# back.
# Usage: layering_test.sh SOURCE_DIR
set -euo pipefail
cd "$1"
status=0
check() {   # check ROOM FORBIDDEN...
  local room=$1
  shift
  for forbidden in "$@"; do
    if grep -rn --include='*.hpp' --include='*.cpp' "#include \"$forbidden/" "$room"; then
      echo "FAIL: $room/ includes $forbidden/ (the dependency runs back)" >&2
      status=1
    fi
  done
}
check kernels sweeps model io app python
check sweeps model io app python
check model io app python
check io app python
check app python
check python app
# The methods.mpm block is parsed in io/ only.
if grep -rn "parse_mpm_settings(" model app python kernels sweeps; then
  echo "FAIL: methods.mpm parsed outside io/" >&2
  status=1
fi
[ "$status" -eq 0 ] && echo "layering: kernels, sweeps <- model <- io <- app, python; methods.mpm parsed in io/ only"
exit "$status"
