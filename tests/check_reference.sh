#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The API reference is complete: every public name of include/dalembert/*.h has its entry in
# the generated HTML, found through Doxygen's own index pages.
#
# usage: check_reference.sh <doxygen> <Doxyfile> <html dir> <header dir>
# Runs Doxygen (a warning -- an undocumented member, a broken doc comment -- fails it), then
# lists from the headers every DAL_API declaration (functions and exported objects), every
# static inline function, typedef, enum and enumerator, struct and DAL_ macro (include guards
# and macros #undef'd in the same header aside), and looks up each name in the index pages
# (globals*.html for file members, annotated.html for structs). A name is found when its index
# entry links to a page that exists and holds the linked anchor. Prints the count of each kind
# and fails on any name without an entry.
set -euo pipefail
doxygen=$1 doxyfile=$2 html=$3 headers=$4

rm -rf "$html"
mkdir -p "$(dirname "$html")"
if ! "$doxygen" "$doxyfile"; then
  echo "reference: Doxygen failed (warnings are errors); its log:" >&2
  log=$(sed -n 's/^WARN_LOGFILE *= *//p' "$doxyfile")
  [ -f "$log" ] && cat "$log" >&2
  exit 1
fi
[ -f "$html/globals.html" ] || { echo "reference: no $html/globals.html" >&2; exit 1; }

# the public names, as "kind name header" lines
names=$(for h in "$headers"/*.h; do
  awk -v file="$(basename "$h")" '
  function trim(s) { gsub(/^[ \t]+|[ \t]+$/, "", s); return s }
  function emit(kind, name) { if (name != "") print kind, name, file }
  # the identifier right before the first "(" of s ("(*name)" for a pointer typedef)
  function name_before_paren(s,   i, pre) {
    if (match(s, /\(\*[ \t]*[A-Za-z_][A-Za-z_0-9]*[ \t]*\)/)) {
      pre = substr(s, RSTART + 2, RLENGTH - 3); return trim(pre)
    }
    i = index(s, "("); pre = trim(substr(s, 1, i - 1))
    if (match(pre, /[A-Za-z_][A-Za-z_0-9]*$/)) return substr(pre, RSTART, RLENGTH)
    return ""
  }
  function last_ident(s) {
    gsub(/\[[^]]*\]/, "", s); s = trim(s)
    if (match(s, /[A-Za-z_][A-Za-z_0-9]*$/)) return substr(s, RSTART, RLENGTH)
    return ""
  }
  # a complete statement at file level (head: the text before "{", or the whole statement)
  function statement(head, body, tail,   kind, tag, items, n, i, it) {
    head = trim(head)
    if (head == "") return
    if (body == "" && head !~ /\{/) {
      if (head ~ /^DAL_API/) {
        if (index(head, "(")) emit("function", name_before_paren(head))
        else emit("object", last_ident(head))
      } else if (head ~ /^typedef/) {
        if (index(head, "(")) emit("typedef", name_before_paren(head))
        else emit("typedef", last_ident(head))
      }
      return
    }
    if (head ~ /^static inline/) { emit("function", name_before_paren(head)); return }
    if (match(head, /(struct|enum)[ \t]+[A-Za-z_][A-Za-z_0-9]*/)) {
      tag = substr(head, RSTART, RLENGTH); kind = (tag ~ /^struct/) ? "struct" : "enum"
      sub(/^(struct|enum)[ \t]+/, "", tag)
      emit(kind, tag)
      if (kind == "enum") {
        n = split(body, items, ",")
        for (i = 1; i <= n; i++) {
          it = trim(items[i])
          if (match(it, /^[A-Za-z_][A-Za-z_0-9]*/)) emit("enumerator", substr(it, RSTART, RLENGTH))
        }
      }
      if (head ~ /^typedef/) emit("typedef", last_ident(tail))
    }
  }
  BEGIN { skip = 0; ns = 0 }
  cont { cont = ($0 ~ /\\$/); next }     # continuation lines of a macro
  /^[ \t]*#/ {
    line = $0; cont = (line ~ /\\$/)
    if (line ~ /^[ \t]*#[ \t]*ifdef[ \t]+__cplusplus/) { st[++ns] = "cplusplus"; skip++ ; next }
    if (line ~ /^[ \t]*#[ \t]*ifdef[ \t]+DAL_DOXYGEN/) { st[++ns] = "doc"; next }
    if (line ~ /^[ \t]*#[ \t]*if/) { st[++ns] = "other"; next }
    if (line ~ /^[ \t]*#[ \t]*else/) {
      if (st[ns] == "doc") { st[ns] = "nodoc"; skip++ }
      next
    }
    if (line ~ /^[ \t]*#[ \t]*endif/) {
      if (st[ns] == "cplusplus" || st[ns] == "nodoc") skip--
      ns--; next
    }
    if (skip) next
    if (match(line, /#[ \t]*define[ \t]+DAL_[A-Za-z_0-9]*/)) {
      m = substr(line, RSTART, RLENGTH); sub(/#[ \t]*define[ \t]+/, "", m)
      if (m !~ /_H$/ && !(m in seen_macro)) { seen_macro[m] = 1; macros[++nm] = m }
    }
    if (match(line, /#[ \t]*undef[ \t]+DAL_[A-Za-z_0-9]*/)) {
      m = substr(line, RSTART, RLENGTH); sub(/#[ \t]*undef[ \t]+/, "", m); undef[m] = 1
    }
    next
  }
  skip { next }
  { sub(/\/\/.*/, ""); buf = buf " " $0 }
  END {
    for (i = 1; i <= nm; i++) if (!(macros[i] in undef)) emit("macro", macros[i])
    gsub(/\/\*([^*]|\*+[^*\/])*\*+\//, " ", buf)
    depth = 0; head = ""; body = ""; tail = ""; state = "head"
    L = length(buf)
    for (i = 1; i <= L; i++) {
      c = substr(buf, i, 1)
      if (state == "head") {
        if (c == "{") { state = "body"; depth = 1; body = " "; continue }
        if (c == ";") { statement(head, "", ""); head = ""; continue }
        head = head c
      } else if (state == "body") {
        if (c == "{") depth++
        if (c == "}") { depth--; if (depth == 0) {
          if (head ~ /\)[ \t]*$/) { statement(head, body, ""); head = ""; body = ""; state = "head" }
          else state = "tail"
          continue } }
        body = body c
      } else {
        if (c == ";") { statement(head, body, tail); head = ""; body = ""; tail = ""; state = "head"; continue }
        tail = tail c
      }
    }
  }' "$h"
done)

# the index: "name file#anchor" from Doxygen's global-member pages and the struct list
index=$(cat "$html"/globals*.html |
  grep -o '<li>[A-Za-z_0-9]*\(()\)\{0,1\}&#160;:&#160;<a class="el" href="[^"]*"' |
  sed 's|<li>\([A-Za-z_0-9]*\)\(()\)\{0,1\}&#160;:&#160;<a class="el" href="\([^"]*\)"|\1 \3|')
structs=$(grep -o 'href="struct[A-Za-z_0-9]*\.html"[^>]*>[A-Za-z_0-9]*<' "$html/annotated.html" |
  sed 's|href="\([^"]*\)"[^>]*>\([A-Za-z_0-9]*\)<|\2 \1|')

# the status codes: the reference reads a spelled-out copy of DAL_STATUS_LIST (base.h); the
# copy must give the same names and values
list=$(sed -n 's/^ *X(\(DAL_[A-Z_]*\), \(-\{0,1\}[0-9]*\),.*/\1 \2/p' "$headers/base.h")
copy=$(sed -n 's/^ *\(DAL_[A-Z_]*\) = \(-\{0,1\}[0-9]*\), *\/\/\/<.*/\1 \2/p' "$headers/base.h")
fail=0
if [ -z "$list" ] || [ "$list" != "$copy" ]; then
  echo "reference: base.h's documented status enum differs from DAL_STATUS_LIST:" >&2
  diff <(echo "$list") <(echo "$copy") >&2 || true
  fail=1
fi

missing=0
declare -A count
while read -r kind name file; do
  [ -n "$kind" ] || continue
  if [ "$kind" = struct ]; then
    target=$(awk -v n="$name" '$1 == n { print $2; exit }' <<<"$structs")
  else
    target=$(awk -v n="$name" '$1 == n { print $2; exit }' <<<"$index")
  fi
  ok=0
  if [ -n "$target" ]; then
    page=${target%%#*}
    anchor=${target#*#}
    if [ -f "$html/$page" ]; then
      if [ "$anchor" = "$target" ] || grep -q "id=\"$anchor\"" "$html/$page"; then ok=1; fi
    fi
  fi
  if ((ok)); then
    count[$kind]=$((${count[$kind]:-0} + 1))
  else
    echo "reference: MISSING $kind $name ($file): no entry in the index${target:+ (link $target broken)}" >&2
    missing=$((missing + 1))
  fi
done <<<"$names"

total=0
summary=""
for k in function object typedef struct enum enumerator macro; do
  summary="$summary ${count[$k]:-0} ${k}s,"
  total=$((total + ${count[$k]:-0}))
done
echo "reference: $total public names found in the HTML index:${summary%,}"
if ((missing > 0 || fail)); then
  echo "reference: FAILED, $missing names without an entry" >&2
  exit 1
fi
