#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The README's install and link lines, run as written: in a fresh copy of the sources (the
# files git knows), with a fresh $HOME and no PKG_CONFIG_PATH, the README's ```sh block after
# "Install and link" runs line by line (build, install to "$HOME/.local", pkg-config, compile
# app.c, run it) and its ```cmake block is the CMakeLists.txt of a project that builds the same
# app.c with find_package. app.c is the README's first program (examples/first_program.c); both
# builds must print its theta(10), checked against the exact elliptic answer. Then the installed
# `dalembert --version` runs from $HOME/.local/bin without LD_LIBRARY_PATH, and a program that
# calls sin (tests/consumer/sin_app.c) links with the README's lines verbatim and with the
# README's and the guide's CMake blocks.
# usage: scripts/readme_install.sh   (CI: .ci/run; takes a Release build of the library)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/src" "$work/home" "$work/app"

# the blocks, by their place in the README
block() { # <language>: the first ```<language> block after the "Install and link" paragraph
  awk -v lang="$1" '
    /^Install and link/ { seen = 1 }
    seen && !inb && $0 == "```" lang { inb = 1; next }
    inb && /^```/ { exit }
    inb { print }' "$root/README.md"
}
block sh >"$work/install.sh"
block cmake >"$work/app/CMakeLists.txt"
for f in install.sh app/CMakeLists.txt; do
  if [ ! -s "$work/$f" ]; then
    echo "readme install: no block for $f after 'Install and link' in README.md" >&2
    exit 1
  fi
done
echo "== the README's install and link lines:"
cat "$work/install.sh"

# a clean copy of the sources, the README's program as app.c, and a checker of its answer
git -C "$root" ls-files -z --cached --others --exclude-standard |
  tar -C "$root" --null -T - -cf - | tar -C "$work/src" -xf -
cp "$root/examples/first_program.c" "$work/src/app.c"
cp "$root/examples/first_program.c" "$work/app/app.c"
cc -std=c11 -O2 -I"$root/tests" "$root/tests/consumer/check_first.c" -o "$work/check_first" -lm

# run as a user would: from the source folder, with a home of its own
(cd "$work/src" && env -u PKG_CONFIG_PATH -u LD_LIBRARY_PATH HOME="$work/home" \
  bash -euo pipefail -x "$work/install.sh") | tee "$work/sh.out"
"$work/check_first" <"$work/sh.out"

echo "== the README's CMake project (find_package), with -DCMAKE_PREFIX_PATH=\"\$HOME/.local\""
cat "$work/app/CMakeLists.txt"
env -u LD_LIBRARY_PATH HOME="$work/home" cmake -S "$work/app" -B "$work/app/build" \
  -DCMAKE_PREFIX_PATH="$work/home/.local" >/dev/null
cmake --build "$work/app/build"
env -u LD_LIBRARY_PATH "$work/app/build/app" | tee "$work/cmake.out"
"$work/check_first" <"$work/cmake.out"

# the installed command from the prefix, with no LD_LIBRARY_PATH: its run path finds the
# libraries beside it (libdalembert, libdalembert_mpi when built)
echo "== the installed dalembert command, from \$HOME/.local/bin, without LD_LIBRARY_PATH"
version=$(awk '/^#define DAL_VERSION_(MAJOR|MINOR|PATCH) / { v = v (v == "" ? "" : ".") $3 }
  END { print v }' "$root/include/dalembert/base.h")
got=$(env -u LD_LIBRARY_PATH "$work/home/.local/bin/dalembert" --version)
if [ "$got" != "dalembert $version" ]; then
  echo "readme install: the installed dalembert --version said '$got', not 'dalembert $version'" >&2
  exit 1
fi
env -u LD_LIBRARY_PATH "$work/home/.local/bin/dalembert" run \
  "$root/examples/scenes/sicm_oscillator.scene" --no-progress >"$work/run.csv"
echo "$got; run of sicm_oscillator.scene: $(wc -l <"$work/run.csv") lines"

# a program that calls sin, linked with the README's lines verbatim (its export, cc and ./app
# lines) and with the README's and the guide's CMake blocks
echo "== a program calling sin, with the README's link lines"
cp "$root/tests/consumer/sin_app.c" "$work/src/app.c"
grep -E '^(export PKG_CONFIG_PATH|cc |\./app)' "$work/install.sh" >"$work/link.sh"
(cd "$work/src" && env -u PKG_CONFIG_PATH -u LD_LIBRARY_PATH HOME="$work/home" \
  bash -euo pipefail -x "$work/link.sh")
awk '/^## 1\. Install and link/ { seen = 1 }
  seen && !inb && $0 == "```cmake" { inb = 1; next }
  inb && /^```/ { exit }
  inb { print }' "$root/docs/guide.md" >"$work/guide.cmake"
for which in readme guide; do
  echo "== a program calling sin, with the ${which}'s CMake block"
  mkdir -p "$work/sin-$which"
  cp "$root/tests/consumer/sin_app.c" "$work/sin-$which/app.c"
  if [ "$which" = readme ]; then
    cp "$work/app/CMakeLists.txt" "$work/sin-$which/"
  else
    cp "$work/guide.cmake" "$work/sin-$which/CMakeLists.txt"
  fi
  cat "$work/sin-$which/CMakeLists.txt"
  env -u LD_LIBRARY_PATH HOME="$work/home" cmake -S "$work/sin-$which" \
    -B "$work/sin-$which/build" -DCMAKE_PREFIX_PATH="$work/home/.local" >/dev/null
  cmake --build "$work/sin-$which/build"
  env -u LD_LIBRARY_PATH "$work/sin-$which/build/app"
done
echo "readme install: the README's install, pkg-config and find_package lines work as written;"
echo "the installed dalembert runs from the prefix; a program calling sin links with each"
