#!/usr/bin/env bash
# README command 1: installs what is missing, builds, and runs the reference study (the nine
# landslide-barrier cases L1-L3 x B1-B3): prints the comparison table of the methods and the
# barrier masses for a 0.5 m tolerable displacement, and writes results/reference/ (one HDF5 file
# per case, comparison.txt, comparison.json, and a PNG per case under plots/).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/ci/setup.sh"
build="${LSI_BUILD_DIR:-$root/build}"
out="$root/results/reference"
mkdir -p "$out"
scenes=("$root"/scenes/reference/L?-B?.json)
"$build/drivers/lsi" compare "${scenes[@]}" --out-dir "$out" --max-displacement 0.5 \
  --summary-json "$out/comparison.json" | tee "$out/comparison.txt"
MPLCONFIGDIR="$out/.mplconfig" /usr/bin/python3 "$root/drivers/lsi_plot.py" "$out"/L?-B?.h5 \
  --out-dir "$out/plots" >/dev/null
rm -rf "$out/.mplconfig"
echo "results, comparison tables and plots written to ${out#$root/}/"
