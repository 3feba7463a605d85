#!/usr/bin/env bash
# plot_kinds_test.sh KIND LSI_EXE SOURCE_DIR OUT_DIR
# The plot scripts on fresh files of each kind, written by the real `lsi`:
#   sweep         a small Monte Carlo study (lsi sweep) through app/lsi_plot.py (which hands it
#                 to app/lsi_sweep_plot.py): one PNG per method and output; a sweep without an
#                 ok sample, and a file of another kind given to lsi_sweep_plot.py, exit
#                 non-zero
#   verification  a short, coarse dam break with wall pressure bands (lsi run of an mpm_case):
#                 the energies/forces/front PNG and the walls PNG; a file with nothing to plot
#                 exits non-zero with a message
#   impact        a coarse MPM impact whose barrier slides out of the domain, beside the closed
#                 forms (the empirical one's displacement far larger): the plot keeps the others
#                 on scale, marks the empirical curve off scale, notes where the MPM run was
#                 cut short and draws the tolerable displacement
#   calibration   lsi calibrate on two coarse scenes, app/lsi_calibration_plot.py on its file and
#                 on the same file with the fitted scalars as 0-d datasets in scalars/
# Each PNG must exist, be a PNG and be more than 10 kB (a figure with drawn data).
set -euo pipefail
if [ $# -ne 4 ]; then
  echo "usage: $0 sweep|verification|impact|calibration LSI_EXE SOURCE_DIR OUT_DIR" >&2
  exit 2
fi
kind=$1
lsi=$2
src=$3
out=$4
py=/usr/bin/python3
rm -rf "$out"
mkdir -p "$out"
export MPLCONFIGDIR="$out/mplconfig"   # keep matplotlib's cache out of $HOME
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}

source "$(dirname "${BASH_SOURCE[0]}")/check_png.sh"

expect_failure() {   # expect_failure MESSAGE COMMAND...: non-zero exit and MESSAGE on stderr
  local message=$1 rc
  shift
  set +e
  "$@" >"$out/stdout.txt" 2>"$out/stderr.txt"
  rc=$?
  set -e
  if [ "$rc" -eq 0 ]; then
    echo "FAIL: '$*' exited 0" >&2
    exit 1
  fi
  if ! grep -q -- "$message" "$out/stderr.txt"; then
    echo "FAIL: '$*': the message '$(cat "$out/stderr.txt")' lacks '$message'" >&2
    exit 1
  fi
}

case "$kind" in
sweep)
  cat >"$out/study.json" <<JSON
{"name": "plot-test", "scene": "$src/scenes/former-reference/L1-B1.json",
 "inputs": [
   {"path": "/landslide/velocity_m_s", "distribution": "truncated-normal",
    "mean": 6.0, "sd": 1.5, "min": 1.0, "max": 15.0},
   {"path": "/barrier/base_friction", "distribution": "uniform", "min": 0.3, "max": 0.7}],
 "design": "monte-carlo", "samples": 200, "seed": 11,
 "methods": ["empirical", "analytical"], "outputs": ["peak_force", "final_displacement"],
 "thresholds": [{"output": "final_displacement", "above": 0.5},
                {"output": "peak_force", "above": 200000}]}
JSON
  "$lsi" sweep "$out/study.json" --out "$out/study.h5" --progress none >/dev/null
  $py "$src/app/lsi_plot.py" "$out/study.h5" --out-dir "$out/png" --max-displacement 0.5 \
    >"$out/written.txt"
  for m in empirical analytical; do
    for o in peak_force final_displacement; do
      check_png "$out/png/study-$m-$o.png"
    done
  done
  if [ "$(wc -l <"$out/written.txt")" -ne 4 ]; then
    echo "FAIL: expected 4 PNG paths printed, got: $(cat "$out/written.txt")" >&2
    exit 1
  fi
  # A sweep whose samples all failed has nothing to plot.
  $py - "$out/study.h5" "$out/failed.h5" <<'PY'
import shutil, sys
import h5py
shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "a") as f:
    f["samples/status"][...] = 3
PY
  expect_failure "nothing to plot" $py "$src/app/lsi_plot.py" "$out/failed.h5" --out-dir "$out/png"
  $py -c 'import sys, h5py; h5py.File(sys.argv[1], "w").create_group("mpm")' "$out/run.h5"
  expect_failure "not an lsi sweep file" \
    $py "$src/app/lsi_sweep_plot.py" "$out/run.h5" --out-dir "$out/png"
  ;;
verification)
  "$lsi" run "$src/scenes/verification/dam-break-front.json" --progress none \
    --set /methods/mpm/cell_size_m=0.00714 --set /methods/mpm/end_time_s=0.25 \
    --set /methods/mpm/wall_band_m=0.02 --out "$out/dam.h5" >/dev/null
  $py "$src/app/lsi_plot.py" "$out/dam.h5" --out-dir "$out/png" >/dev/null
  check_png "$out/png/dam.png"
  check_png "$out/png/dam-walls.png"
  # Every verification panel drawn: energies, residual, wall reactions, front.
  $py - "$src/app" "$out/dam.h5" <<'PY'
import sys
sys.dont_write_bytecode = True
sys.path.insert(0, sys.argv[1])
import matplotlib.figure
import lsi_plot
figures = []
save = matplotlib.figure.Figure.savefig
matplotlib.figure.Figure.savefig = lambda fig, *a, **k: (figures.append(fig), save(fig, *a, **k))
lsi_plot.plot_file(sys.argv[2], sys.argv[2] + ".png.d")
labels = [ax.get_ylabel() for ax in figures[0].axes]
expected = ["energy", "energy residual", "reaction of the walls", "front"]
for e in expected:
    if not any(label.startswith(e) for label in labels):
        sys.exit(f"FAIL: no panel '{e}' among {labels}")
if any(not ax.lines for ax in figures[0].axes):
    sys.exit(f"FAIL: a panel without a curve among {labels}")
PY
  # A result with nothing to plot (an MPM group with only its time) is an error.
  $py - "$out/empty.h5" <<'PY'
import sys
import h5py, numpy as np
with h5py.File(sys.argv[1], "w") as f:
    f.create_group("mpm")["time"] = np.linspace(0.0, 1.0, 5)
PY
  expect_failure "nothing to plot" $py "$src/app/lsi_plot.py" "$out/empty.h5" --out-dir "$out/png"
  ;;
impact)
  "$lsi" run "$src/scenes/former-reference/L1-B1.json" --progress none \
    --set /methods/mpm/cell_size_m=0.5 --set /barrier/base_friction=0.1 \
    --set /landslide/velocity_m_s=12 --out "$out/slide.h5" >/dev/null
  $py "$src/app/lsi_plot.py" "$out/slide.h5" --out-dir "$out/png" --max-displacement 0.5 \
    >/dev/null
  check_png "$out/png/slide.png"
  $py - "$src/app" "$out/slide.h5" <<'PY'
import sys
sys.dont_write_bytecode = True
sys.path.insert(0, sys.argv[1])
import h5py
import matplotlib.figure
import lsi_plot
with h5py.File(sys.argv[2]) as f:
    if f["mpm"].attrs["end_state"] != "barrier_left_domain":
        sys.exit("FAIL: the test scene's barrier did not leave the domain: "
                 + str(f["mpm"].attrs["end_state"]))
    largest = {m: float(f[m]["barrier_displacement"][()].max()) for m in f}
figures = []
save = matplotlib.figure.Figure.savefig
matplotlib.figure.Figure.savefig = lambda fig, *a, **k: (figures.append(fig), save(fig, *a, **k))
lsi_plot.plot_file(sys.argv[2], sys.argv[2] + ".png.d", tolerance=0.5)
fig = figures[0]
ax = next(a for a in fig.axes if a.get_ylabel().startswith("barrier displacement"))
bottom, top = ax.get_ylim()
others = max(v for m, v in largest.items() if m != "empirical")
# The empirical barrier slides far beyond the others: its curve runs off the panel, whose scale
# is the other methods' (they stay on it).
if largest["empirical"] < 10 * others:
    sys.exit(f"FAIL: the scene no longer makes the empirical displacement an outlier: {largest}")
if not (others <= top < 0.5 * largest["empirical"]):
    sys.exit(f"FAIL: displacement axis up to {top}, displacements {largest}")
legend = [t.get_text() for t in ax.get_legend().get_texts()]
for want in ("empirical (off scale)", "tolerable displacement 0.5 m"):
    if want not in legend:
        sys.exit(f"FAIL: '{want}' not in the displacement legend {legend}")
# Beside it, every curve whole on a log scale.
log = [a for a in fig.axes if a.get_yscale() == "log"]
if len(log) != 1 or len([l for l in log[0].get_lines() if l.get_label() in largest]) != 3:
    sys.exit("FAIL: no log-scale displacement panel with the three methods")
notes = " ".join(t.get_text() for t in fig.texts)
for want in ("mpm: the barrier left the modelled domain at t = ",
             "empirical: displacement off scale"):
    if want not in notes:
        sys.exit(f"FAIL: no note '{want}' in '{notes}'")
PY
  ;;
calibration)
  for s in L1-B1 L1-B3; do
    $py - "$src/scenes/former-reference/$s.json" "$out/c-$s.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["name"] = "c-" + scene["name"]
scene["methods"]["mpm"]["cell_size_m"] = scene["landslide"]["thickness_m"] / 4
scene["barrier"]["fixed"] = scene["name"].endswith("B3")
json.dump(scene, open(sys.argv[2], "w"))
PY
  done
  "$lsi" calibrate "$out/c-L1-B1.json" "$out/c-L1-B3.json" --grid 21x11 --progress none \
    --out "$out/cal.h5" >/dev/null
  $py "$src/app/lsi_calibration_plot.py" "$out/cal.h5" --out-dir "$out/png" --tolerance 0.2 \
    >/dev/null
  check_png "$out/png/cal_maps.png"
  check_png "$out/png/cal_errors.png"
  # The same file with every numeric case and group scalar as a 0-d dataset in scalars/ (the
  # result files' layout) and no such attributes draws the same maps.
  $py - "$out/cal.h5" "$out/cal-datasets.h5" <<'PY'
import shutil, sys
import h5py, numpy as np
shutil.copy(sys.argv[1], sys.argv[2])
with h5py.File(sys.argv[2], "a") as f:
    for g in list(f["cases"].values()) + list(f["groups"].values()):
        s = g.create_group("scalars")
        for k in list(g.attrs):
            if isinstance(g.attrs[k], (float, np.floating)):
                s[k] = float(g.attrs[k])
                del g.attrs[k]
PY
  $py "$src/app/lsi_calibration_plot.py" "$out/cal-datasets.h5" --out-dir "$out/png" >/dev/null
  check_png "$out/png/cal-datasets_maps.png"
  if ! cmp -s "$out/png/cal_maps.png" "$out/png/cal-datasets_maps.png"; then
    echo "FAIL: the maps differ between scalars as attributes and as 0-d datasets" >&2
    exit 1
  fi
  $py -c 'import sys, h5py; h5py.File(sys.argv[1], "w").create_group("mpm")' "$out/none.h5"
  expect_failure "no /cases" $py "$src/app/lsi_calibration_plot.py" "$out/none.h5" \
    --out-dir "$out/png"
  ;;
*)
  echo "$0: unknown kind '$kind' (sweep, verification, impact, calibration)" >&2
  exit 2
  ;;
esac
echo "OK: $kind plots in $out"
