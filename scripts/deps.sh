#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Install dalembert's build dependencies on Debian (bookworm) when missing.
# As root: installs with apt-get. Otherwise: prints the exact install line and exits 1.
set -euo pipefail
pkgs=(build-essential cmake pkg-config libsundials-dev libsuitesparse-dev liblapacke-dev
      libopenblas-dev gnuplot-nox libopenmpi-dev openmpi-bin doxygen python3
      chromium) # chromium: the viewer's browser tests (ctest view_*)
[[ "${DAL_WITH_FUZZ:-0}" == 1 ]] && pkgs+=(clang libclang-rt-14-dev valgrind)
[[ "${DAL_WITH_VALGRIND:-0}" == 1 ]] && pkgs+=(valgrind)
[[ "${DAL_WITH_FORMAT:-0}" == 1 ]] && pkgs+=(clang-format)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then exit 0; fi
line="apt-get update && apt-get install -y --no-install-recommends ${missing[*]}"
if [[ $(id -u) -ne 0 ]]; then
  echo "dalembert: missing packages: ${missing[*]}" >&2
  echo "dalembert: install them as root with:" >&2
  echo "  sudo sh -c '$line'" >&2
  exit 1
fi
echo "dalembert: installing ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
