#!/usr/bin/env bash
# Checks that every tracked C++ source is formatted as .clang-format says. Prints the files that
# are not (with `clang-format -i FILE` as the fix) and exits 1; exits 0 when all are.
#   usage: bash ci/format_check.sh [--fix]     (--fix formats them in place)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
if ! command -v clang-format >/dev/null; then
  echo "ci/format_check.sh: clang-format is not installed (bash ci/setup.sh installs it)" >&2
  exit 1
fi
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.h' | grep -v '^tests/fuzz/corpus/')
else  # a source tree without git (an archive): every source below the root but the build trees
  mapfile -t files < <(find . \( -path './build*' -o -path './.git' -o -path './tests/fuzz/corpus' \) \
    -prune -o \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \) -print | sed 's|^\./||' | sort)
fi
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if [ ${#bad[@]} -gt 0 ]; then
  printf '%s\n' "${bad[@]}"
  echo "ci/format_check.sh: ${#bad[@]} of ${#files[@]} files not formatted (clang-format -i FILE, or bash ci/format_check.sh --fix)" >&2
  exit 1
fi
echo "ci/format_check.sh: ${#files[@]} files formatted"
