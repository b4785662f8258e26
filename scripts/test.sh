#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 2: install dependencies, build, and run the whole ctest suite.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh" "$@"
bdir=${DAL_BUILD_DIR:-$root/build}
cd "$bdir"
ctest --output-on-failure -j "$(nproc)"
