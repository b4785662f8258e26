#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Valgrind memcheck of every example's --check run, the bad-input, reliability and API-sweep
# suites and the fuzz corpus (plus 200 pseudo-random fuzz inputs).
#
# usage: scripts/valgrind.sh        (DAL_VALGRIND_BUILD_DIR: build directory, default
#                                    build-valgrind; a plain build, no sanitizers; an existing
#                                    configured build directory is reused as it is)
# Fails on any memory error or definite/indirect leak. "Still reachable" blocks (SUNDIALS'
# and OpenBLAS' process-lifetime allocations) are not errors.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
DAL_WITH_VALGRIND=1 "$root/scripts/deps.sh"
bdir=${DAL_VALGRIND_BUILD_DIR:-$root/build-valgrind}
if [[ ! -f "$bdir/CMakeCache.txt" ]]; then
  cmake -S "$root" -B "$bdir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDAL_BUILD_BENCH=OFF >/dev/null
fi
if grep -q "^DAL_SANITIZE:BOOL=ON" "$bdir/CMakeCache.txt"; then
  echo "valgrind: $bdir is a sanitizer build; use a plain one" >&2
  exit 1
fi
cmake --build "$bdir" -j "$(nproc)"
export OPENBLAS_NUM_THREADS=1
vg=(valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect
    --show-leak-kinds=definite,indirect --track-origins=yes)
runs=()
for name in $(sed -n 's/^ *dal_example(\([A-Za-z0-9_]*\)).*/\1/p' "$root/examples/CMakeLists.txt"); do
  runs+=("$bdir/examples/$name --check")
done
runs+=("$bdir/tests/test_bad_input")
runs+=("$bdir/tests/test_reliability")
runs+=("$bdir/tests/test_api_sweep $root/include/dalembert")
runs+=("$bdir/tests/fuzz_replay $root/tests/fuzz/corpus --random 200 7")
fail=0
for run in "${runs[@]}"; do
  read -r -a cmd <<<"$run"
  start=$SECONDS
  if "${vg[@]}" "${cmd[@]}" >"$bdir/valgrind.out" 2>"$bdir/valgrind.err"; then
    echo "valgrind: ok    $(basename "${cmd[0]}") ($((SECONDS - start)) s)"
  else
    rc=$?
    fail=1
    echo "valgrind: FAIL  $(basename "${cmd[0]}") (exit $rc; 99 = memory error or leak)"
    tail -n 40 "$bdir/valgrind.err"
  fi
done
if ((fail)); then
  echo "valgrind: FAILED" >&2
  exit 1
fi
echo "valgrind: clean (${#runs[@]} programs)"
