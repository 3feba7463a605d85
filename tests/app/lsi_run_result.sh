#!/usr/bin/env bash
# lsi_run_result.sh OUT.h5: writes a fresh result with the real `lsi run` (LSI_EXE, LSI_SCENE).
set -euo pipefail
"$LSI_EXE" run "$LSI_SCENE" --out "$1" >/dev/null
