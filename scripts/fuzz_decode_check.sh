#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Does every fuzz input decode to the same scene under gcc and clang? (A reproducer found by the
# clang fuzzer must reproduce in the gcc-built replay test.)
#
# usage: scripts/fuzz_decode_check.sh [LIBDIR [extra fuzz_replay arguments]]
#   LIBDIR  directory holding a plain (not sanitized) shared libdalembert; default: build one
#           in $DAL_DECODE_BUILD_DIR (build-decode)
# Compiles tests/fuzz/fuzz_model.c and replay.c with gcc and with clang against the same
# library, replays tests/fuzz/corpus (and the extra arguments) with FZ_DIGEST=1, which prints
# per input a digest of every status, message and final state it produced, and compares.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
libdir=${1:-}
if [[ -z $libdir ]]; then
  bdir=${DAL_DECODE_BUILD_DIR:-$root/build-decode}
  cmake -S "$root" -B "$bdir" -DDAL_BUILD_TESTS=OFF -DDAL_BUILD_EXAMPLES=OFF \
    -DDAL_BUILD_BENCH=OFF >/dev/null
  cmake --build "$bdir" -j 2 >/dev/null
  libdir=$bdir
fi
(($# > 0)) && shift
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export OPENBLAS_NUM_THREADS=1 FZ_DIGEST=1
for cc in gcc clang; do
  if ! command -v "$cc" >/dev/null; then
    echo "fuzz decode check: $cc not found" >&2
    exit 1
  fi
  "$cc" -std=c11 -O2 -I"$root/include" "$root/tests/fuzz/fuzz_model.c" \
    "$root/tests/fuzz/replay.c" -L"$libdir" -Wl,-rpath,"$libdir" -ldalembert -lm \
    -o "$work/replay-$cc"
  "$work/replay-$cc" "$root/tests/fuzz/corpus" "$@" >"$work/$cc.txt"
done
n=$(grep -c "fz-digest" "$work/gcc.txt" || true)
if ! cmp -s "$work/gcc.txt" "$work/clang.txt"; then
  echo "fuzz decode check: inputs decode differently under gcc and clang:" >&2
  diff "$work/gcc.txt" "$work/clang.txt" | head -40 >&2
  exit 1
fi
echo "fuzz decode check: $n inputs decode identically under gcc and clang"
