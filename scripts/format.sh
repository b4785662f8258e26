#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The formatting check of CI: every C file of the library, its tests, examples and benchmarks
# as .clang-format writes it. `scripts/format.sh --fix` rewrites them in place instead.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
DAL_WITH_FORMAT=1 "$root/scripts/deps.sh"
cd "$root"
mapfile -t files < <(git ls-files '*.c' '*.h' | grep -v '^tests/fuzz/corpus')
if [[ "${1:-}" == "--fix" ]]; then
  clang-format -i "${files[@]}"
  exit 0
fi
if ! clang-format --dry-run -Werror "${files[@]}"; then
  echo "format: the files above differ from .clang-format; run scripts/format.sh --fix" >&2
  exit 1
fi
echo "format: ${#files[@]} files as .clang-format writes them"
