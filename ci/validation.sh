#!/usr/bin/env bash
# The validation against experiments, regenerated in one command: runs the dam-break scenes of
# scenes/verification/ at three cell sizes with the built `lsi`, writes the figures (model against
# experiment, with the experiment's scatter) and a summary table into results/validation/, and
# rewrites the generated table of docs/vv/validation.md. Builds nothing: build first
# (cmake --build build -j2); LSI_BUILD_DIR names another build directory.
#
#   bash ci/validation.sh            every case and resolution (a few minutes on 2 cores)
#   bash ci/validation.sh --quick    the ctest resolution only (under a minute)
#   bash ci/validation.sh --fresh    rerun every case (runs are otherwise kept in
#                                    results/validation/runs/ and reused)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
exec /usr/bin/python3 "$root/ci/validation_report.py" "$@"
