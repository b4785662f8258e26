#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 2: install dependencies, build, and run the whole ctest suite.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# tests on, whatever the build folder cached (an install configured with DAL_BUILD_TESTS=OFF in
# the same folder would otherwise leave test binaries older than the sources, and ctest would
# report their old pass): the last -D wins, and every test binary is rebuilt before ctest runs
"$root/scripts/build.sh" "$@" -DDAL_BUILD_TESTS=ON
bdir=${DAL_BUILD_DIR:-$root/build}
cd "$bdir"
ctest --output-on-failure --no-tests=error -j "$(nproc)"
