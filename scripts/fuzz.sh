#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Bounded libFuzzer run of tests/fuzz/fuzz_model.c or tests/fuzz/fuzz_scene.c (clang, ASan +
# UBSan + LeakSanitizer).
#
# usage: scripts/fuzz.sh [extra libFuzzer flags]
#   DAL_FUZZ_TARGET    fuzz_model (default) or fuzz_scene (scene files, long lists, formulas and
#                      the symbolic printer with its time bound)
#   DAL_FUZZ_SECONDS   time budget (default 60)
#   DAL_FUZZ_BUILD_DIR build directory (default build-fuzz)
# New interesting inputs go to $DAL_FUZZ_BUILD_DIR/fuzz-corpus (the committed seed corpus
# tests/fuzz/corpus is only read); a crashing input is written to fuzz-artifacts/ and the
# script exits non-zero. Add a crash reproducer to tests/fuzz/corpus once it is fixed, so
# ctest replays it in every build.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
DAL_WITH_FUZZ=1 "$root/scripts/deps.sh"
bdir=${DAL_FUZZ_BUILD_DIR:-$root/build-fuzz}
secs=${DAL_FUZZ_SECONDS:-60}
target=${DAL_FUZZ_TARGET:-fuzz_model}
case "$target" in
  fuzz_model) seeds="$root/tests/fuzz/corpus" ;;
  fuzz_scene) seeds="$root/tests/fuzz/corpus_scene" ;;
  *) echo "fuzz: DAL_FUZZ_TARGET is fuzz_model or fuzz_scene, not '$target'" >&2; exit 64 ;;
esac
cmake -S "$root" -B "$bdir" -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DDAL_FUZZ=ON -DDAL_SANITIZE=ON -DBUILD_SHARED_LIBS=OFF -DDAL_BUILD_EXAMPLES=OFF \
  -DDAL_BUILD_BENCH=OFF >/dev/null
cmake --build "$bdir" -j "$(nproc)" --target "$target"
work="$bdir/fuzz-corpus-$target"
art="$bdir/fuzz-artifacts-$target"
mkdir -p "$work" "$art"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:allocator_may_return_null=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export OPENBLAS_NUM_THREADS=1
echo "== fuzzing $target for ${secs} s (corpus: $work + $seeds)"
set +e
"$bdir/tests/$target" -max_total_time="$secs" -rss_limit_mb=2048 -timeout=120 \
  -max_len=1024 -print_final_stats=1 -artifact_prefix="$art/" "$@" \
  "$work" "$seeds" 2>"$bdir/fuzz.log"
rc=$?
set -e
grep -E "^(#[0-9]+.*DONE|stat::|Done|==[0-9]+==ERROR|SUMMARY|.*invariant violated)" \
  "$bdir/fuzz.log" || true
if ((rc != 0)); then
  echo "fuzz: FAILED (libFuzzer exit $rc); log: $bdir/fuzz.log, reproducer in $art/" >&2
  tail -n 60 "$bdir/fuzz.log" >&2
  exit 1
fi
echo "fuzz: no crash, leak or invariant violation in ${secs} s"
