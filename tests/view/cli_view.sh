#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# SPDX-FileCopyrightText: 2026 dalembert engineers
# The command line's outputs: run --columns and view, and their bad input (a non-zero exit
# naming the culprit, no file left behind).  cli_view.sh DALEMBERT SCENES_DIR WORK_DIR
set -u
cli=$1 scenes=$2 work=$3
fails=0
fail() { echo "cli_view: $*" >&2; fails=$((fails + 1)); }
rm -rf "$work" && mkdir -p "$work" || exit 1
cd "$work" || exit 1

# a selection: the header names the columns
"$cli" run "$scenes/driven_pendulum.scene" -o cols.csv --columns 't,x:*,y:b?b,P,W' ||
  fail "run --columns failed"
[ "$(head -1 cols.csv)" = "t,x:bob,y:bob,P,W" ] || fail "header: $(head -1 cols.csv)"
[ "$(wc -l < cols.csv)" = 10002 ] || fail "rows: $(wc -l < cols.csv)"

# an unknown column: exit non-zero, the culprit named, no file
"$cli" run "$scenes/driven_pendulum.scene" -o bad.csv --columns 't,x:bobby' 2> err.txt &&
  fail "an unknown column was accepted"
grep -q "bobby" err.txt || fail "the message does not name the column: $(cat err.txt)"
[ ! -e bad.csv ] || fail "bad.csv was left behind"

# view: one complete page
"$cli" view "$scenes/sicm_oscillator.scene" -o osc.html 2> /dev/null || fail "view failed"
head -c 15 osc.html | grep -q '<!DOCTYPE html>' || fail "osc.html does not start as HTML"
tail -1 osc.html | grep -q '</html>' || fail "osc.html is not complete"
# default name: the scene's with .html, next to it
cp "$scenes/bead_ring_below.scene" bead.scene
"$cli" view bead.scene --t1 1 2> /dev/null && [ -s bead.html ] || fail "view without -o"

# view into a folder that does not exist: non-zero, nothing written
"$cli" view "$scenes/sicm_oscillator.scene" -o nodir/x.html 2> err.txt &&
  fail "a page into a missing folder was reported written"
grep -q "nodir/x.html" err.txt || fail "the message does not name the file: $(cat err.txt)"

# a scene without particles: refused, no page (not even a partial one)
printf 'dim 0\ncoord x q=1 v=0\nlagrangian = 1/2*xdot^2 - 1/2*x^2\nrun t1=1 dt=0.1\n' > lag.scene
"$cli" view lag.scene -o lag.html 2> err.txt && fail "a scene without particles was drawn"
grep -q "no particles" err.txt || fail "the message: $(cat err.txt)"
[ ! -e lag.html ] && [ ! -e lag.html.part ] || fail "lag.html left behind"

# picture: a multi-exposure SVG; a bad list of times leaves nothing
"$cli" picture "$scenes/driven_pendulum.scene" -o pend.svg --times 0,0.5,1 ||
  fail "picture failed"
[ "$(grep -c '<g opacity' pend.svg)" = 3 ] || fail "pend.svg has not 3 exposures"
"$cli" picture "$scenes/driven_pendulum.scene" -o bad.svg --times 1,0.5 2> err.txt &&
  fail "decreasing times were accepted"
[ ! -e bad.svg ] && [ ! -e bad.svg.part ] || fail "bad.svg left behind"
"$cli" picture "$scenes/driven_pendulum.scene" -o bad.svg --times 0,x 2> err.txt &&
  fail "--times 0,x was accepted"

[ $fails = 0 ] && echo "cli_view: all checks passed"
exit $((fails > 0))
