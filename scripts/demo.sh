#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# README command 1: install dependencies, build, and run the flagship demo.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$root/scripts/build.sh"
bdir=${DAL_BUILD_DIR:-$root/build}
"$bdir/examples/demo"
