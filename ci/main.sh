#!/usr/bin/env bash
# README command 1: installs what is missing, builds, and runs the reference study (the nine
# landslide-barrier cases L1-L3 x B1-B3): prints the comparison table of the methods and the
# barrier masses for a 0.5 m tolerable displacement, and writes results/reference/ (one HDF5 file
# per case, comparison.txt, comparison.json, and a PNG per case under plots/).
#
#   bash ci/main.sh                       the study as shipped (MPM: dry, 16 cells per thickness)
#   bash ci/main.sh --saturated [CELLS]   the same nine with a saturated (two-phase) MPM landslide
#                                         at CELLS cells through the flow's thickness (default 8)
#                                         into results/reference-saturated/ (scenes/ holds the
#                                         scenes it ran); why the shipped study runs dry, and what
#                                         the saturated runs do and do not resolve: docs/mpm.md
#                                         ("The reference study: settings and resolution"),
#                                         docs/two_phase.md ("Impacts")
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
saturated=0
if [ "${1:-}" = "--saturated" ]; then
  saturated=1
  cells="${2:-8}"
  if ! [[ "$cells" =~ ^[0-9]+$ ]] || [ "$cells" -lt 4 ] || [ $# -gt 2 ]; then
    echo "ci/main.sh: --saturated CELLS must be a whole number of cells through the flow's" \
         "thickness, at least 4 (the MPM's limit: a cell at most a quarter of it); got" \
         "'${*:2}'" >&2
    exit 2
  fi
elif [ $# -gt 0 ]; then
  echo "ci/main.sh: unknown argument '$1' (usage: bash ci/main.sh [--saturated [CELLS]])" >&2
  exit 2
fi
bash "$root/ci/setup.sh"
build="${LSI_BUILD_DIR:-$root/build}"
scenes=("$root"/scenes/reference/L?-B?.json)
out="$root/results/reference"
if [ "$saturated" = 1 ]; then
  out="$root/results/reference-saturated"
  mkdir -p "$out/scenes"
  # The shipped scenes with the saturated landslide at the requested resolution.
  /usr/bin/python3 "$root/ci/saturated_scenes.py" "$out/scenes" "$cells" "${scenes[@]}"
  scenes=("$out"/scenes/L?-B?.json)
fi
mkdir -p "$out"
"$build/drivers/lsi" compare "${scenes[@]}" --out-dir "$out" --max-displacement 0.5 \
  --summary-json "$out/comparison.json" | tee "$out/comparison.txt"
MPLCONFIGDIR="$out/.mplconfig" /usr/bin/python3 "$root/drivers/lsi_plot.py" "$out"/L?-B?.h5 \
  --out-dir "$out/plots" >/dev/null
rm -rf "$out/.mplconfig"
echo "results, comparison tables and plots written to ${out#$root/}/"
