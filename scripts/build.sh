#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Configure and build dalembert into build/ (or $DAL_BUILD_DIR), after the dependency step.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/deps.sh"
bdir=${DAL_BUILD_DIR:-$root/build}
cmake -S "$root" -B "$bdir" -DCMAKE_BUILD_TYPE=${DAL_BUILD_TYPE:-RelWithDebInfo} "$@" >/dev/null
cmake --build "$bdir" -j "$(nproc)"
