#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Line and branch coverage of the library (src/, constraints/) reached by the fuzz corpus.
#
# usage: scripts/coverage.sh [extra fuzz_replay arguments, e.g. --random 1000 1]
#   DAL_COVERAGE_BUILD_DIR  build directory (default build-cov)
# Builds the static library and tests/fuzz/replay.c with clang's source-based coverage
# (-fprofile-instr-generate -fcoverage-mapping, Debug), replays tests/fuzz/corpus (and the
# extra arguments), and prints llvm-cov's per-file report, the totals, and the library
# sources the replay never linked (a static library only links what is called).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bdir=${DAL_COVERAGE_BUILD_DIR:-$root/build-cov}
flags="-fprofile-instr-generate -fcoverage-mapping"
cmake -S "$root" -B "$bdir" -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=Debug \
  -DBUILD_SHARED_LIBS=OFF -DDAL_BUILD_EXAMPLES=OFF -DDAL_BUILD_BENCH=OFF \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" >/dev/null
cmake --build "$bdir" -j 2 --target fuzz_replay >/dev/null
prof="$bdir/coverage"
rm -rf "$prof"
mkdir -p "$prof"
export OPENBLAS_NUM_THREADS=1
LLVM_PROFILE_FILE="$prof/replay-%p.profraw" "$bdir/tests/fuzz_replay" "$root/tests/fuzz/corpus" "$@"
llvm-profdata merge -sparse "$prof"/*.profraw -o "$prof/replay.profdata"
report=$(llvm-cov report "$bdir/tests/fuzz_replay" -instr-profile="$prof/replay.profdata" \
  "$root/src" "$root/constraints")
echo "$report"
# totals: llvm-cov's columns are regions, functions, lines, branches (each: total, missed, %)
echo "$report" | awk '/^TOTAL/ {printf "coverage from the corpus: lines %s, branches %s\n", $10, $13}'
missing=""
for f in "$root"/src/*/*.c "$root"/constraints/*.c; do
  rel=${f#"$root"/}
  grep -q "$rel" <<<"$report" || missing="$missing $rel"
done
echo "library sources not linked by the replay:${missing:- none}"
