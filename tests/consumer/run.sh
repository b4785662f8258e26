#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Consumer check driver (run by ctest), one step per mode:
#   run.sh install   <build dir> <prefix>
#   run.sh cmake     <prefix> <work dir> <libdir> <cc> <shared|static> [<extra C/link flags>]
#   run.sh pkgconfig <prefix> <work dir> <libdir> <cc> <shared|static> [<extra C/link flags>]
# install: a fresh `cmake --install` of the main build into <prefix>. cmake: configure and
# build tests/consumer as a separate project with CMAKE_PREFIX_PATH=<prefix>, then run it.
# pkgconfig: compile tests/consumer/main.c with the flags `pkg-config` gives for dalembert.pc
# found through PKG_CONFIG_PATH in <prefix>, then run it. Extra flags (sanitizers) are passed
# to the compiler and linker so that the consumer matches an instrumented library.
# Both ways also build the README's first program (examples/first_program.c) as the README
# says -- find_package + dalembert::dalembert, or `cc app.c $(pkg-config --cflags --libs
# dalembert) -Wl,-rpath,<prefix>/<libdir>` -- run it without LD_LIBRARY_PATH (the rpath note of
# docs/guide.md) and check its theta(10) against the exact elliptic answer (check_first.c).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mode=$1

if [ "$mode" = install ]; then
  build=$2 prefix=$3
  rm -rf "$prefix"
  cmake --install "$build" --prefix "$prefix"
  exit 0
fi

if [ "$mode" = embed ]; then
  # run.sh embed <source dir> <work dir> <cc> [<extra flags>]: dalembert inside another
  # project (FetchContent from the source folder, i.e. add_subdirectory): the library builds,
  # its tests, examples and benchmarks do not, and the README's program runs
  src=$2 work=$3 cc=$4 flags=${5:-}
  rm -rf "$work"
  cmake -S "$here/embed" -B "$work" -DDAL_SOURCE_DIR="$src" -DDAL_WITH_MPI=OFF \
    -DCMAKE_C_COMPILER="$cc" -DCMAKE_C_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" \
    -DCMAKE_BUILD_TYPE=Release
  cmake --build "$work" -j 2
  "$work/first_program" >"$work/first_program.out"
  "$work/check_first" <"$work/first_program.out"
  exit 0
fi

prefix=$2 work=$3 libdir=$4 cc=$5 kind=$6 flags=${7:-}
rm -rf "$work"
mkdir -p "$work"
# the README's program must find the library by its rpath alone: it runs with LD_LIBRARY_PATH
# as the caller had it, without the prefix
caller_ld=${LD_LIBRARY_PATH-}
first_program() {
  LD_LIBRARY_PATH="$caller_ld" "$work/first_program" >"$work/first_program.out"
  "$work/check_first" <"$work/first_program.out"
}
export LD_LIBRARY_PATH="$prefix/$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"

case "$mode" in
  cmake)
    cmake -S "$here" -B "$work" -DCMAKE_PREFIX_PATH="$prefix" -DDAL_CONSUMER_PREFIX="$prefix" \
      -DCMAKE_C_COMPILER="$cc" -DCMAKE_C_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" \
      -DCMAKE_BUILD_TYPE=Release -DDAL_CONSUMER_MPI="${DAL_CONSUMER_MPI:-0}"
    cmake --build "$work"
    "$work/consumer"
    if [ "${DAL_CONSUMER_MPI:-0}" = 1 ]; then "$work/consumer_mpi"; fi
    first_program
    ctest --test-dir "$work" -L dalembert_verify --output-on-failure --no-tests=error
    ;;
  pkgconfig)
    export PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig"
    static=""
    [ "$kind" = static ] && static="--static"
    version=$(pkg-config --modversion dalembert)
    cflags=$(pkg-config --cflags dalembert)
    libs=$(pkg-config $static --libs dalembert)
    echo "pkg-config: version $version, cflags '$cflags', libs '$libs'"
    # the flags must point into the prefix, not to the source tree or a system install
    case "$cflags" in
      *"-I$prefix/"*) ;;
      *) echo "pkg-config cflags do not point into $prefix"; exit 1 ;;
    esac
    # shellcheck disable=SC2086
    "$cc" -std=c11 -Wall -Wextra -pedantic -Werror $flags $cflags \
      -DDAL_EXPECT_VERSION="\"$version\"" "$here/main.c" -o "$work/consumer" $libs -lm
    "$work/consumer"
    # the README's command line, with the rpath of its install note
    # shellcheck disable=SC2086
    "$cc" $flags "$here/../../examples/first_program.c" $cflags $libs \
      -Wl,-rpath,"$prefix/$libdir" -o "$work/first_program"
    "$cc" -std=c11 -Wall -Wextra -pedantic -Werror $flags -I"$here/.." "$here/check_first.c" \
      -o "$work/check_first" -lm
    first_program
    # the MPI library's own .pc file (dalembert_mpi: Requires dalembert, and MPI's flags)
    if [ "${DAL_CONSUMER_MPI:-0}" = 1 ]; then
      mpi_flags=$(pkg-config --cflags --libs dalembert_mpi)
      echo "pkg-config dalembert_mpi: '$mpi_flags'"
      # shellcheck disable=SC2086
      "$cc" -std=c11 -Wall -Wextra -Werror $flags "$here/mpi_main.c" $mpi_flags \
        -o "$work/consumer_mpi"
      "$work/consumer_mpi"
    elif pkg-config --exists dalembert_mpi; then
      echo "dalembert_mpi.pc installed by a build without MPI"
      exit 1
    fi
    ;;
  *)
    echo "usage: run.sh install|cmake|pkgconfig|embed ..." >&2
    exit 2
    ;;
esac
