#!/usr/bin/env bash
# grano course as a student uses it: every exercise's parameters are flags,
# a flag an exercise does not use is refused by name, a range is stated as
# the check applies it, alpha = 1 and the broken-up cooling state at
# alpha = 0.5 run to an explained result, and the figures' axes fit their
# data (figure_axes.py). TAP.
set -u
. "$(dirname "$0")/tap.sh"
GRANO=$1
HERE=$(dirname "$0")

# refused: exit 2, the flag named, nothing written
refused() { # description flag args...
    local what=$1 flag=$2; shift 2
    "$GRANO" course "$@" --out "$tmp/never" >"$tmp/out" 2>"$tmp/err"
    local rc=$?
    if [ $rc = 2 ] && grep -qF -- "$flag" "$tmp/err" && [ ! -e "$tmp/never/maxwell.h5" ] &&
       [ ! -e "$tmp/never/cooling.h5" ] && [ ! -e "$tmp/never/pressure.h5" ]; then ok "$what"
    else notok "$what (exit $rc)"; fi
}
refused "maxwell refuses --alpha by name" "--alpha is not a parameter" maxwell --quick --alpha 0.5
refused "pressure refuses --eta by name" "--eta is not a parameter" pressure --quick --eta 0.1
refused "cooling refuses --runs by name" "--runs is not a parameter" cooling --quick --runs 3
refused "cooling refuses --time by name" "--time is not a parameter" cooling --quick --time 10
refused "--eta and --box together refused" "--eta and --box" cooling --quick --eta 0.1 --box 50
refused "--alpha 0 refused, the range stated open at 0" "--alpha: '0' is not a number in (0, 1]" cooling --quick --alpha 0
refused "--alpha 1.5 refused" "(0, 1]" cooling --quick --alpha 1.5
refused "--eta 0.8 refused" "--eta: '0.8' is not a number in (0, 0.75)" cooling --quick --eta 0.8
refused "disks that do not fit the box refused naming --box" "--box: 400 disks do not fit" maxwell --quick --n 400 --box 15
refused "maxwell's last stage must follow 3 collisions per disk" "--collisions" maxwell --quick --collisions 2
refused "--n 1 refused" "--n: '1' is not an integer in [2" cooling --quick --n 1

# the flags change what runs
"$GRANO" course maxwell --quick --n 64 --eta 0.1 --runs 2 --collisions 6 --out "$tmp/m" >"$tmp/out" 2>"$tmp/err"
rc=$?; cp "$tmp/out" "$tmp/err"
if [ $rc = 0 ] && grep -q "maxwell: 64 elastic disks in a 22.42 x 22.42 box, 2 runs" "$tmp/out" &&
   grep -qE "^ +6\.0 " "$tmp/out"; then ok "maxwell --n 64 --eta 0.1 --runs 2 --collisions 6: the box, runs and stages"
else notok "maxwell with its flags (exit $rc)"; fi

"$GRANO" course pressure --quick --box 10 --n 25 --time 50 --out "$tmp/p" >"$tmp/out" 2>"$tmp/err"
rc=$?; cp "$tmp/out" "$tmp/err"
if [ $rc = 0 ] && grep -q "in a 10 x 10 box" "$tmp/out" && grep -q "N = 25, against V0" "$tmp/out" &&
   grep -qE "^  1 +0\.0100 " "$tmp/out"; then ok "pressure --box 10 --n 25 --time 50: the box, the sweep scaled to it"
else notok "pressure with its flags (exit $rc)"; fi

# alpha = 1: an elastic gas keeps its temperature; the laws hold trivially
"$GRANO" course cooling --quick --alpha 1 --n 500 --collisions 2 --out "$tmp/c1" >"$tmp/out" 2>"$tmp/err"
rc=$?; cp "$tmp/out" "$tmp/err"
if [ $rc = 0 ] && grep -q "alpha = 1," "$tmp/out" && grep -q "Haff time tau = inf" "$tmp/out"; then
    ok "cooling --alpha 1 runs: tau infinite, T stays T0"
else notok "cooling --alpha 1 (exit $rc)"; fi

# alpha = 0.5: the homogeneous state breaks up; said and drawn, exit 0
"$GRANO" course cooling --quick --alpha 0.5 --out "$tmp/c5" >"$tmp/out" 2>"$tmp/err"
rc=$?; cp "$tmp/out" "$tmp/err"
if [ $rc = 0 ] && grep -q "the homogeneous cooling state broke up" "$tmp/out" && [ -s "$tmp/c5/cooling_state.png" ]; then
    ok "cooling --alpha 0.5: the break-up explained, cooling_state.png drawn"
else notok "cooling --alpha 0.5 (exit $rc)"; fi

# the figures' axes against their data
if command -v gnuplot >/dev/null && [ -x /usr/bin/python3 ]; then
    "$GRANO" course all --quick --out "$tmp/all" >/dev/null 2>"$tmp/err" || notok "course all --quick"
    if /usr/bin/python3 "$HERE/figure_axes.py" "$tmp/all" "$tmp/c5" >"$tmp/axes" 2>&1; then
        ok "figure axes fit their data ($(grep -c '^ok' "$tmp/axes") axes)"
    else cp "$tmp/axes" "$tmp/err"; notok "figure axes fit their data"; fi
fi
finish
