#!/usr/bin/env bash
# The calibration of the closed forms against the reference study's saturated MPM
# (docs/theory/calibration.md): lambda, tau and a1, a2, tau per case and per group (fixed, free) beside
# the paper's, the closed forms' errors against the MPM with each method's run time, and the
# misfit maps, for both objectives.
#
#   bash ci/calibrate.sh    -> results/calibration/<model>-<objective>.{h5,txt}, *_maps.png and
#                              *_errors.png for both barrier models (paper, momentum) and both
#                              objectives (nrms, peak-duration), and the tables of
#                              docs/vv/calibration_results.md
#
# The MPM histories are those of results/reference/ (bash ci/main.sh, run first if they are
# missing); `lsi calibrate` runs the MPM itself for any case whose stored run is of other settings.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ $# -gt 0 ]; then
  echo "ci/calibrate.sh: takes no arguments (usage: bash ci/calibrate.sh)" >&2
  exit 2
fi
bash "$root/ci/setup.sh"
build="${LSI_BUILD_DIR:-$root/build}"
scenes=("$root"/scenes/reference/L?-B?.json "$root"/scenes/reference/L?-B?-fixed.json)
runs="$root/results/reference"
for s in "${scenes[@]}"; do
  if [ ! -f "$runs/$(basename "${s%.json}").h5" ]; then
    bash "$root/ci/main.sh"
    break
  fi
done
out="$root/results/calibration"
mkdir -p "$out"
files=()
for model in paper momentum; do
  for objective in nrms peak-duration; do
    f="$out/$model-$objective"
    "$build/app/lsi" calibrate "${scenes[@]}" --results-dir "$runs" --objective "$objective" \
      --barrier-model "$model" --out "$f.h5" > "$f.txt"
    MPLCONFIGDIR="$out/.mplconfig" /usr/bin/python3 "$root/app/lsi_calibration_plot.py" \
      "$f.h5" --out-dir "$out" > /dev/null
    files+=("$f.h5")
  done
done
rm -rf "$out/.mplconfig"
/usr/bin/python3 "$root/ci/calibration_report.py" --out "$root/docs/vv/calibration_results.md" \
  "${files[@]}"
echo "calibration written to ${out#$root/}/ and docs/vv/calibration_results.md"
