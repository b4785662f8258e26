# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# What the benchmark scripts share (sourced, not run): the --quick/--full argument, the Release
# build of the benchmarks, and the start of the callgrind scripts.

# bench_mode USAGE [ARG]: prints --quick (ARG empty or --quick) or --full; any other ARG prints
# the usage line USAGE and exits 2
bench_mode() {
  case "${2:-}" in
    --quick | "") echo --quick ;;
    --full) echo --full ;;
    *) echo "usage: $1" >&2; exit 2 ;;
  esac
}

# bench_build SRC BDIR TARGET [JOBS] [CMAKE ARGS...]: the benchmark TARGET alone (no tests, no
# examples) in a Release build of SRC in BDIR, on JOBS processes (default 2)
bench_build() {
  local src=$1 bdir=$2 target=$3 jobs=${4:-2}
  shift $(($# < 4 ? $# : 4))
  cmake -S "$src" -B "$bdir" -DCMAKE_BUILD_TYPE=Release "$@" -DDAL_BUILD_TESTS=OFF \
    -DDAL_BUILD_EXAMPLES=OFF -DDAL_BUILD_BENCH=ON >/dev/null
  cmake --build "$bdir" -j "$jobs" --target "$target"
}

# ir_start NAME DIR: without valgrind and callgrind_annotate says so and exits 0 (skipped); else
# creates DIR and a scratch folder $tmp, removed when the script exits
ir_start() {
  if ! command -v valgrind >/dev/null || ! command -v callgrind_annotate >/dev/null; then
    echo "$1: valgrind not installed; skipped" >&2
    exit 0
  fi
  mkdir -p "$2"
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
}
