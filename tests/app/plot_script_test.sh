#!/usr/bin/env bash
# plot_script_test.sh MAKE_SAMPLE_RESULT LSI_PLOT_PY OUT_DIR
# Writes a fresh result file, plots it with app/lsi_plot.py and checks the PNG.
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 MAKE_SAMPLE_RESULT LSI_PLOT_PY OUT_DIR" >&2
  exit 2
fi
make_sample=$1
plot_script=$2
out_dir=$3

rm -rf "$out_dir"
mkdir -p "$out_dir"
export MPLCONFIGDIR="$out_dir/mplconfig"   # keep matplotlib's cache out of $HOME
source "$(dirname "${BASH_SOURCE[0]}")/check_png.sh"

"$make_sample" "$out_dir/sample.h5"
/usr/bin/python3 "$plot_script" "$out_dir/sample.h5" --out-dir "$out_dir/png"

png="$out_dir/png/sample.png"
check_png "$png"
size=$(stat -c %s "$png")

# LSI_FACE_PNG=1: the result has the face's pressure bands, and their plot must be written too.
if [ "${LSI_FACE_PNG:-0}" = 1 ]; then
  face="$out_dir/png/sample-face.png"
  if [ ! -f "$face" ] || [ "$(stat -c %s "$face")" -le 10240 ]; then
    echo "FAIL: $face was not written (or is under 10 kB)" >&2
    exit 1
  fi
fi

# A missing file must be an error with a message.
if /usr/bin/python3 "$plot_script" "$out_dir/does_not_exist.h5" --out-dir "$out_dir/png" 2>"$out_dir/err.txt"; then
  echo "FAIL: lsi_plot.py succeeded on a missing file" >&2
  exit 1
fi
if [ ! -s "$out_dir/err.txt" ]; then
  echo "FAIL: lsi_plot.py gave no message for a missing file" >&2
  exit 1
fi
echo "OK: $png ($size bytes)"
