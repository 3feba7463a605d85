#!/usr/bin/env bash
# The accuracy study (issue 6): installs what is missing, builds, runs scenes/studies/accuracy.json
# with `lsi accuracy` (MPM series over cells per thickness, points per cell, Courant number, the
# transfer schemes and the two drag updates; the closed forms timed on the same scene) and draws
# the work-precision and convergence diagrams. Writes results/accuracy/: accuracy.md (tables),
# accuracy.json, *.png, runs/ (each run's histories and record). About 3-4 minutes on 2 cores.
# Finished runs are kept: a killed study continues where it stopped; delete results/accuracy to
# start afresh (docs/vv/accuracy.md). Another study writes to results/<its file name without .json>,
# e.g. scenes/studies/accuracy-overtopping.json (the overtopped volume, docs/vv/accuracy.md).
# usage: ci/accuracy.sh [STUDY.json]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/ci/setup.sh"
build="${LSI_BUILD_DIR:-$root/build}"
study="${1:-$root/scenes/studies/accuracy.json}"
out="$root/results/$(basename "$study" .json)"   # results/accuracy for the default study
mkdir -p "$out"
OMP_NUM_THREADS="${OMP_NUM_THREADS:-$(nproc)}" OMP_PROC_BIND=false OMP_WAIT_POLICY=passive \
  "$build/app/lsi" accuracy "$study" --out "$out" --resume
MPLCONFIGDIR="$out/.mplconfig" /usr/bin/python3 "$root/app/lsi_accuracy_plot.py" \
  "$out/accuracy.json" >/dev/null
rm -rf "$out/.mplconfig"
echo "accuracy tables and plots written to ${out#$root/}/"
