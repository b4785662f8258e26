#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The README's two Python routes, as a person runs them: `cmake --install` into a prefix puts
# the package on that prefix's Python path, and `pip install --no-build-isolation ./python`
# builds it offline against the installed library (pkg-config); each then solves a scene.
#   install_check.sh <build dir> <source dir> <python3> <python install dir>
set -euo pipefail
build=$1 src=$2 py=$3 pydir=$4
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
check='import dalembert as d, sys
r = d.Scene.load(sys.argv[1]).solve((0, 1))
assert r.success and r.t.size == 101, r
print(d.__file__)'
scene=$src/examples/scenes/driven_pendulum.scene
# 1. cmake --install
where=$(cd "$tmp" && PYTHONPATH="$tmp/prefix/$pydir" "$py" -c "$check" "$scene")
[[ $where == "$tmp/prefix/$pydir/dalembert/__init__.py" ]] || { echo "imported $where" >&2; exit 1; }
# 2. pip against the installed library (a copy of python/: pip builds in the tree it is given)
cp -r "$src/python" "$tmp/pysrc"
pc=$(dirname "$(find "$tmp/prefix" -name dalembert.pc | head -1)")
PKG_CONFIG_PATH=$pc "$py" -m pip install --no-build-isolation --no-index --no-deps -q --root-user-action=ignore \
  --target "$tmp/pip" "$tmp/pysrc" 2>&1 | grep -v "^\s*$" >&2 || true
where=$(cd "$tmp" && PYTHONPATH="$tmp/pip" "$py" -c "$check" "$scene")
[[ $where == "$tmp/pip/dalembert/__init__.py" ]] || { echo "imported $where" >&2; exit 1; }
echo "install_check: cmake --install and pip install both import and solve"
