#!/usr/bin/env bash
# lsi as an installed CMake package, end to end: installs the build into a fresh prefix, builds
# the consumer project (consumer/) against it with find_package(lsi CONFIG), and checks what its
# programs print:
#   closed_form_peak (lsi::closed_form): the two-body peak force and impulse against the same
#     quantities computed here by another route, F_peak = (3/4) mu v^2 / (lambda L) and I = mu v
#     with mu = m1 m2 / (m1 + m2) (docs/theory/models.md), for a free and a fixed barrier;
#   scene_peaks (lsi::io, lsi::model): the peak force of every method of a small scene against
#     the installed `lsi run` on the same scene;
# and, where the build has the Python module (MODULE_DIR not empty), the installed module
# imported with PYTHONPATH naming its folder in the prefix (PYTHON_INSTALL_DIR, relative to the
# prefix or absolute), not the build's: its closed forms over an array against the build's
# module's on the same scene (the same compiled code: equal to the last bit).
# Usage: install_test.sh CMAKE BUILD_DIR SOURCE_DIR WORK_DIR CXX_COMPILER [MODULE_DIR
#        PYTHON_INSTALL_DIR]
set -euo pipefail
cmake=$1 build=$2 source=$3 work=$4 cxx=$5 module_dir=${6:-} python_dir=${7:-}
here="$source/tests/install"
rm -rf "$work"
mkdir -p "$work"
prefix="$work/prefix"

"$cmake" --install "$build" --prefix "$prefix" >"$work/install.log"
for f in bin/lsi lib/cmake/lsi/lsiConfig.cmake lib/cmake/lsi/lsiConfigVersion.cmake \
         include/lsi/kernels/closed_form/two_body_model.hpp include/lsi/model/scene.hpp; do
  [ -e "$prefix/$f" ] || { echo "FAIL: the install has no $f" >&2; exit 1; }
done
"$prefix/bin/lsi" --version

if [ -n "$module_dir" ]; then
  case "$python_dir" in
    /*) installed_module_dir=$python_dir ;;
    *) installed_module_dir=$prefix/$python_dir ;;
  esac
  compgen -G "$installed_module_dir/lsi*.so" >/dev/null ||
    { echo "FAIL: the install has no Python module lsi in $installed_module_dir" >&2; exit 1; }
  /usr/bin/python3 - "$module_dir" "$installed_module_dir" "$here/tiny-impact.json" <<'PY'
import json
import os
import subprocess
import sys

build_dir, installed_dir, scene = sys.argv[1:4]
# Each module in a fresh interpreter of its own, with only its folder on the path.
EVALUATE = """
import json, os, sys
import numpy as np
import lsi
r = lsi.closed_forms(sys.argv[1], velocity_m_s=np.linspace(2.0, 9.0, 15),
                     methods=["empirical", "analytical"])
print(json.dumps({"file": os.path.realpath(lsi.__file__), "version": lsi.__version__,
                  "values": {m: {k: [float(x).hex() for x in v] for k, v in o.items()}
                             for m, o in r.items()}}))
"""


def evaluate(module_dir):
    env = dict(os.environ, PYTHONPATH=module_dir, PYTHONNOUSERSITE="1")
    out = subprocess.run([sys.executable, "-c", EVALUATE, scene], env=env, check=True,
                         capture_output=True, text=True, cwd="/").stdout
    return json.loads(out)


built, installed = evaluate(build_dir), evaluate(installed_dir)
failures = 0
if not installed["file"].startswith(os.path.realpath(installed_dir) + os.sep):
    print(f"FAIL: import lsi with PYTHONPATH={installed_dir} loaded {installed['file']}")
    failures += 1
if installed["version"] != built["version"]:
    print(f"FAIL: installed lsi.__version__ {installed['version']} != {built['version']}")
    failures += 1
for method, outputs in built["values"].items():
    for name, values in outputs.items():
        got = installed["values"].get(method, {}).get(name)
        ok = got == values
        print(f"{'ok  ' if ok else 'FAIL'} installed module's {method} {name} over "
              f"{len(values)} velocities equals the build's")
        failures += not ok
sys.exit(1 if failures else 0)
PY
else
  echo "the Python module is not built: its install is not checked"
fi

"$cmake" -S "$here/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$prefix" \
         -DCMAKE_CXX_COMPILER="$cxx" >"$work/configure.log" ||
  { cat "$work/configure.log"; exit 1; }
"$cmake" --build "$work/consumer" -j 2 >"$work/build.log" || { cat "$work/build.log"; exit 1; }

# One MPM thread for both runs: the same compiled solver then does the same arithmetic, so the
# two programs agree to the last digit (several threads sum the grid's contributions in a varying
# order).
export OMP_NUM_THREADS=1 OMP_PROC_BIND=false

/usr/bin/python3 - "$work/consumer" "$prefix/bin/lsi" "$here/tiny-impact.json" <<'PY'
import json
import math
import subprocess
import sys

consumer, lsi, scene = sys.argv[1:4]
# Two routes to the same exact quantity in double precision: tens of operations of a few ulp.
TWO_ROUTES_REL = 1e-12
# The same compiled code on one thread: equal but for the decimal printing of the two programs.
SAME_CODE_REL = 1e-12
failures = 0


def check(what, got, want, rel):
    global failures
    ok = math.isfinite(got) and abs(got - want) <= rel * abs(want)
    print(f"{'ok  ' if ok else 'FAIL'} {what}: {got!r} (expected {want!r}, rel. tol. {rel:g})")
    failures += not ok


def run(*args):
    return subprocess.run(list(args), check=True, capture_output=True, text=True).stdout


# landslide mass (kg/m), velocity (m/s), equivalent length (m), barrier mass (kg/m), lambda, tau
for m1, v, length, m2, lam, tau in [(7200.0, 4.0, 4.0, 5000.0, 0.41, 0.25),
                                    (3.1e4, 7.5, 11.0, math.inf, 0.72, 0.17)]:
    out = dict(line.split() for line in run(f"{consumer}/closed_form_peak", repr(m1), repr(v),
                                                repr(length), repr(m2), repr(lam),
                                                repr(tau)).splitlines())
    mu = m1 if math.isinf(m2) else m1 * m2 / (m1 + m2)
    case = f"m1={m1:g} v={v:g} L={length:g} m2={m2:g}"
    check(f"two-body peak force ({case})", float(out["peak_force"]),
          0.75 * mu * v * v / (lam * length), TWO_ROUTES_REL)
    check(f"two-body impulse ({case})", float(out["impulse"]), mu * v, TWO_ROUTES_REL)

consumer_peaks = {m: float(p) for m, p in
                  (line.split() for line in run(f"{consumer}/scene_peaks", scene).splitlines())}
lsi_run = json.loads(run(lsi, "--progress", "none", "run", scene, "--format", "json"))
if sorted(consumer_peaks) != sorted(lsi_run):
    print(f"FAIL: methods {sorted(consumer_peaks)} against lsi run's {sorted(lsi_run)}")
    failures += 1
for method, result in sorted(lsi_run.items()):
    check(f"{method} peak force of {scene.rsplit('/', 1)[-1]} against lsi run",
          consumer_peaks.get(method, math.nan), result["peak_force"], SAME_CODE_REL)
sys.exit(1 if failures else 0)
PY
