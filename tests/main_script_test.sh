#!/usr/bin/env bash
# main_script_test.sh SOURCE_DIR LSI_EXE OUT_DIR
# README command 1's options: ci/main.sh's argument checks (made before it installs or builds
# anything) and the scenes of its variants (ci/reference_variant.py): the eighteen reference
# scenes with only the asked methods.mpm keys changed, each accepted by lsi (which checks the
# methods.mpm block when it reads a scene).
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 SOURCE_DIR LSI_EXE OUT_DIR" >&2
  exit 2
fi
src=$1
lsi=$2
out=$3
rm -rf "$out"
mkdir -p "$out"

expect_usage_error() {   # expect_usage_error MESSAGE ARGS...: exit code 2 and MESSAGE on stderr
  local message=$1 err rc
  shift
  set +e
  err=$(bash "$src/ci/main.sh" "$@" 2>&1 >/dev/null)
  rc=$?
  set -e
  if [ "$rc" -ne 2 ]; then
    echo "FAIL: ci/main.sh $* exited $rc, expected 2 ($err)" >&2
    exit 1
  fi
  if [[ "$err" != *"$message"* ]]; then
    echo "FAIL: ci/main.sh $*: the message '$err' lacks '$message'" >&2
    exit 1
  fi
}
expect_usage_error "unknown argument '--bogus'" --bogus
expect_usage_error "at least 4" --cells 3
expect_usage_error "got 'eight'" --cells eight
expect_usage_error "unknown argument 'x'" --cells 8 x

set +e
err=$(/usr/bin/python3 "$src/ci/reference_variant.py" "$out/bad" --cells 2 "$src/scenes/reference/L1-B1.json" 2>&1)
rc=$?
set -e
if [ "$rc" -ne 2 ] || [[ "$err" != *"at least 4"* ]]; then
  echo "FAIL: reference_variant.py with 2 cells: exit $rc, '$err'" >&2
  exit 1
fi

/usr/bin/python3 "$src/ci/reference_variant.py" "$out/scenes" --cells 6 --dry --smooth-base \
  --paper-barrier "$src"/scenes/reference/L?-B?*.json
/usr/bin/python3 - "$src/scenes/reference" "$out/scenes" <<'PY'
import glob, json, os, sys
ref, out = sys.argv[1], sys.argv[2]
paths = sorted(glob.glob(os.path.join(ref, "L?-B?*.json")))
assert len(paths) == 18, paths
for path in paths:
    want = json.load(open(path))
    got = json.load(open(os.path.join(out, os.path.basename(path))))
    mpm = got["methods"]["mpm"]
    h = want["landslide"]["thickness_m"]
    assert abs(mpm["cell_size_m"] - h / 6) <= 1e-12 * h, (path, mpm)
    assert mpm["phases"] == "dry" and got["landslide"]["base_friction"] == 0, (path, got)
    want["methods"]["mpm"].update(cell_size_m=mpm["cell_size_m"], phases="dry")
    want["landslide"]["base_friction"] = 0
    for m in ("empirical", "analytical"):
        assert got["methods"][m]["barrier_model"] == "paper", (path, got["methods"])
        want["methods"][m]["barrier_model"] = "paper"
    assert got == want, path   # nothing else changed
print("variant scenes: 18 checked")
PY
for f in "$out"/scenes/L?-B?*.json; do
  "$lsi" run "$f" --methods analytical --format json >/dev/null
done
echo "main_script_test: ok"
