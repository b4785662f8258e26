#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# Every C code block of README.md and docs/*.md is a program that compiles and runs.
#
#   doc_blocks.sh extract <out dir> <markdown files...>
#   doc_blocks.sh run <out dir> <source root> <program id=executable...>
#
# Fenced blocks by their info string:
#   ```c               a complete program: written to <out dir>/<id>.c (id: file name and the
#                      line of the fence, e.g. guide_56), built by tests/CMakeLists.txt, run
#                      by the ctest doc_blocks; it must exit 0
#   ```c from=PATH     a quotation: every run of lines between "..." lines must occur, line by
#                      line (leading and trailing blanks aside), in PATH (relative to the
#                      source root; an example or test that ctest builds)
#   ```output          what the C block before it prints: each line must occur in the output
#   other languages    (sh, cmake, text, ...) are not C and are left alone
# A ```c block with any other info string is an error. Besides ```output blocks, the prose
# after a program (up to the next block or heading) may quote its output: every "prints `X`"
# there is checked, X ending in "..." standing for any continuation. extract prints the ids
# of the programs, separated by ";" (for CMake); run re-extracts the markdown named in
# <out dir>/sources.txt and fails if the built programs are stale, then runs each program in
# a scratch directory and checks the quoted output and the quotations.
set -euo pipefail
mode=$1
out=$2
shift 2

extract() { # <dir> <md...>: writes <dir>/<id>.c, <id>.expect, quotes.txt, quote_<id>.txt
  local dir=$1 md base
  shift
  mkdir -p "$dir"
  : >"$dir/quotes.txt"
  : >"$dir/errors.txt"
  for md in "$@"; do
    base=$(basename "$md" .md)
    awk -v dir="$dir" -v base="$base" -v md="$md" '
    function flush_prose(   s, q, i) {
      # "prints `X`" in the prose after the last program
      if (last == "" || prose == "") return
      s = prose
      while ((i = index(s, "prints `")) > 0) {
        s = substr(s, i + 8)
        q = index(s, "`")
        if (q == 0) break
        print substr(s, 1, q - 1) >> (dir "/" last ".expect")
        s = substr(s, q + 1)
      }
      prose = ""
    }
    BEGIN { inblock = 0; last = ""; prose = "" }
    {
      line = $0
      if (!inblock && line ~ /^```/) {
        info = substr(line, 4); gsub(/^[ \t]+|[ \t]+$/, "", info)
        flush_prose()
        inblock = 1; start = NR
        kind = "other"
        if (info == "c") {
          kind = "program"; id = base "_" NR
          file = dir "/" id ".c"; printf "" > file
          printf "" > (dir "/" id ".expect")
          print id
        } else if (info ~ /^c[ \t]+from=[^ \t]+$/) {
          kind = "quote"; src = info; sub(/^c[ \t]+from=/, "", src)
          id = base "_" NR
          file = dir "/quote_" id ".txt"; printf "" > file
          print id, src >> (dir "/quotes.txt")
        } else if (info ~ /^c([ \t{]|$)/ || info ~ /^C$/) {
          print md ":" NR ": a C block must be ```c (a program) or ```c from=PATH (a quotation): " info >> (dir "/errors.txt")
        } else if (info == "output") {
          kind = "output"
          if (last == "") print md ":" NR ": an output block without a program before it" >> (dir "/errors.txt")
        }
        next
      }
      if (inblock && line ~ /^```[ \t]*$/) {
        inblock = 0
        if (kind == "program") { close(file); last = id }
        else if (kind == "quote") close(file)
        else if (kind != "output") last = ""
        next
      }
      if (inblock) {
        if (kind == "program" || kind == "quote") print line >> file
        else if (kind == "output") print line >> (dir "/" last ".expect")
        next
      }
      if (line ~ /^#/) { flush_prose(); last = ""; next }
      if (last != "") prose = prose " " line
    }
    END {
      flush_prose()
      if (inblock) print md ":" start ": block not closed" >> (dir "/errors.txt")
    }' "$md"
  done
}

case "$mode" in
  extract)
    # into a fresh folder, then copy what changed (unchanged files keep their times: no rebuild)
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    ids=$(extract "$tmp" "$@")
    mkdir -p "$out"
    printf '%s\n' "$@" >"$tmp/sources.txt"
    for f in "$tmp"/*; do
      cmp -s "$f" "$out/$(basename "$f")" || cp "$f" "$out/"
    done
    for f in "$out"/*.c "$out"/*.expect "$out"/quote_*.txt; do
      [ -e "$f" ] || continue
      [ -e "$tmp/$(basename "$f")" ] || rm -f "$f"
    done
    echo "$ids" | paste -sd';'
    ;;
  run)
    root=$1
    shift
    tmp=$(mktemp -d)
    trap 'rm -rf "$tmp"' EXIT
    mapfile -t sources <"$out/sources.txt"
    extract "$tmp/now" "${sources[@]}" >/dev/null
    fail=0
    if [ -s "$tmp/now/errors.txt" ]; then
      cat "$tmp/now/errors.txt" >&2
      fail=1
    fi
    # the programs built must be the blocks the markdown has now
    for f in "$tmp/now"/*.c "$tmp/now"/*.expect; do
      [ -e "$f" ] || continue
      if ! cmp -s "$f" "$out/$(basename "$f")"; then
        echo "doc blocks: $(basename "$f") changed since the build: rebuild (cmake --build)" >&2
        fail=1
      fi
    done
    nprog=0 nexp=0
    for arg in "$@"; do
      id=${arg%%=*} exe=${arg#*=}
      [ -e "$tmp/now/$id.c" ] || continue # a block that is gone (stale build, reported above)
      mkdir -p "$tmp/run/$id"
      if ! (cd "$tmp/run/$id" && timeout 300 "$exe" >"$tmp/$id.out" 2>"$tmp/$id.err"); then
        echo "doc blocks: $id ($exe) failed; its output:" >&2
        cat "$tmp/$id.out" "$tmp/$id.err" >&2
        fail=1
        continue
      fi
      nprog=$((nprog + 1))
      while IFS= read -r want || [ -n "$want" ]; do
        [ -n "$want" ] || continue
        pat=${want%...}
        if grep -qF -- "$pat" "$tmp/$id.out"; then
          nexp=$((nexp + 1))
        else
          echo "doc blocks: $id does not print '$want'; it printed:" >&2
          cat "$tmp/$id.out" >&2
          fail=1
        fi
      done <"$tmp/now/$id.expect"
    done
    nblocks=$(find "$tmp/now" -name '*.c' | wc -l)
    if ((nprog != nblocks)); then
      echo "doc blocks: $nblocks programs in the markdown, $nprog ran" >&2
      fail=1
    fi
    # quotations: each run of lines between "..." must occur in the quoted file
    nquote=0
    while read -r id src; do
      [ -n "$id" ] || continue
      if [ ! -f "$root/$src" ]; then
        echo "doc blocks: $id quotes $src, which does not exist" >&2
        fail=1
        continue
      fi
      if awk -v id="$id" '
        function trim(s) { gsub(/^[ \t]+|[ \t]+$/, "", s); return s }
        BEGIN { nchunk = 0; n = 0 }
        NR == FNR { t = trim($0); if (t == "...") { nchunk++ } else if (t != "") { chunk[nchunk, ++len[nchunk]] = t }; next }
        { file[++n] = trim($0) }
        END {
          bad = 0
          for (c = 0; c <= nchunk; c++) {
            if (len[c] == 0) continue
            found = 0
            for (i = 1; i + len[c] - 1 <= n && !found; i++) {
              ok = 1
              for (k = 1; k <= len[c] && ok; k++) if (file[i + k - 1] != chunk[c, k]) ok = 0
              if (ok) found = 1
            }
            if (!found) { print "doc blocks: " id ": not in the quoted file: " chunk[c, 1] " ..." > "/dev/stderr"; bad = 1 }
          }
          exit bad
        }' "$tmp/now/quote_$id.txt" "$root/$src"; then
        nquote=$((nquote + 1))
      else
        fail=1
      fi
    done <"$tmp/now/quotes.txt"
    echo "doc blocks: $nprog programs compiled and run, $nexp quoted outputs checked, $nquote quotations found verbatim (markdown: ${#sources[@]} files)"
    exit $fail
    ;;
  *)
    echo "usage: doc_blocks.sh extract|run ..." >&2
    exit 2
    ;;
esac
