#!/usr/bin/env bash
# README command 1: installs what is missing, builds, and runs the reference study (nine
# landslide-barrier cases L1-L3 x B1-B3, each with a free and a fixed barrier): prints the
# comparison table of the methods with the MPM's error bars from the convergence study, and the
# barrier masses for a 0.5 m tolerable displacement; writes results/reference/ (one HDF5 file per
# case, comparison.txt, comparison.json, and a PNG per case under plots/).
#
#   bash ci/main.sh                      the study as shipped (saturated MPM landslide, 8 cells
#                                        through the flow's thickness, base friction 0.2)
#   bash ci/main.sh [--cells N] [--dry] [--smooth-base] [--paper-barrier]
#                                        a variant: N cells through the thickness, the dry
#                                        (single-phase) landslide, the paper's smooth base
#                                        (F1 = 0), the paper's closed forms for a free barrier
#                                        (instead of the momentum-consistent barrier);
#                                        into results/reference-<variant>/ (its scenes
#                                        in scenes/ there); no error bars (the convergence study
#                                        is of the shipped settings: ci/reference_convergence.py)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
usage="usage: bash ci/main.sh [--cells N] [--dry] [--smooth-base] [--paper-barrier]"
variant=() tag=""
while [ $# -gt 0 ]; do
  case "$1" in
    --cells)
      cells="${2:-}"
      if ! [[ "$cells" =~ ^[0-9]+$ ]] || [ "$cells" -lt 4 ]; then
        echo "ci/main.sh: --cells must be a whole number of cells through the flow's thickness," \
             "at least 4 (the MPM's limit: a cell at most a quarter of it); got '$cells'" >&2
        exit 2
      fi
      variant+=(--cells "$cells"); tag+="-$cells"; shift 2 ;;
    --dry) variant+=(--dry); tag+="-dry"; shift ;;
    --smooth-base) variant+=(--smooth-base); tag+="-smooth"; shift ;;
    --paper-barrier) variant+=(--paper-barrier); tag+="-paper"; shift ;;
    *) echo "ci/main.sh: unknown argument '$1' ($usage)" >&2; exit 2 ;;
  esac
done
bash "$root/ci/setup.sh"
build="${LSI_BUILD_DIR:-$root/build}"
scenes=("$root"/scenes/reference/L?-B?.json "$root"/scenes/reference/L?-B?-fixed.json)
out="$root/results/reference"
bars=(--convergence "$root/ci/reference_convergence.json")
if [ ${#variant[@]} -gt 0 ]; then
  out="$root/results/reference$tag"
  /usr/bin/python3 "$root/ci/reference_variant.py" "$out/scenes" "${variant[@]}" "${scenes[@]}"
  scenes=("$out"/scenes/L?-B?.json "$out"/scenes/L?-B?-fixed.json)
  bars=()
fi
mkdir -p "$out"
"$build/app/lsi" compare "${scenes[@]}" --out-dir "$out" --max-displacement 0.5 \
  "${bars[@]}" --verify-design analytical --summary-json "$out/comparison.json" \
  | tee "$out/comparison.txt"
MPLCONFIGDIR="$out/.mplconfig" /usr/bin/python3 "$root/app/lsi_plot.py" "$out"/L?-B?*.h5 \
  --out-dir "$out/plots" --max-displacement 0.5 >/dev/null
rm -rf "$out/.mplconfig"
echo "results, comparison tables and plots written to ${out#$root/}/"
