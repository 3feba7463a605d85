#!/usr/bin/env bash
# lsi_run_result.sh OUT.h5: writes a fresh result with the real `lsi run` (LSI_EXE, LSI_SCENE).
set -euo pipefail
# LSI_SET (optional): one --set override, e.g. the face's pressure bands.
"$LSI_EXE" run "$LSI_SCENE" ${LSI_SET:+--set "$LSI_SET"} --out "$1" >/dev/null
