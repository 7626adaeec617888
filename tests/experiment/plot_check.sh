#!/usr/bin/env bash
# Figures: the gnuplot script saved beside the PNG remakes it; a title with
# an apostrophe survives; GRANO_FIGURES=svg,pdf adds those formats; without
# gnuplot the run says so and how to install it, and keeps the script. TAP.
set -u
. "$(dirname "$0")/tap.sh"
GRANO=$1
SRC=$2
if ! command -v gnuplot >/dev/null; then echo "1..0 # SKIP gnuplot is not installed"; exit 0; fi
scene=$SRC/experiments/scenes/box.ini
run() { "$GRANO" run "$scene" --until 0.05 --set "scene.name=it's a box" --out "$tmp/r.h5" --force -q "$@"; }

run --snapshot "$tmp/a.png" 2>"$tmp/err"
if [ $? = 0 ] && [ -s "$tmp/a.png" ] && grep -q "set title 'it''s a box, t = " "$tmp/a.gp"; then
    ok "snapshot with an apostrophe in its title, script a.gp beside a.png"
else notok "snapshot and script"; fi
rm -f "$tmp/a.png"
if (cd "$tmp" && gnuplot a.gp) 2>"$tmp/err" && [ -s "$tmp/a.png" ]; then ok "gnuplot a.gp remakes a.png"
else notok "gnuplot a.gp"; fi

GRANO_FIGURES=svg,pdf run --snapshot "$tmp/b.png" 2>"$tmp/err"
if [ $? = 0 ] && [ -s "$tmp/b.png" ] && grep -q "<svg" "$tmp/b.svg" && head -c 5 "$tmp/b.pdf" | grep -q "%PDF"; then
    ok "GRANO_FIGURES=svg,pdf: b.svg and b.pdf too"
else notok "svg and pdf"; fi

PATH=/nonexistent run --snapshot "$tmp/c.png" 2>"$tmp/err"
rc=$?
if [ $rc = 1 ] && grep -q "gnuplot is not installed" "$tmp/err" && grep -q "apt-get install gnuplot-nox" "$tmp/err" &&
   [ -s "$tmp/c.gp" ] && [ ! -e "$tmp/c.png" ]; then
    ok "without gnuplot: says so and how to install it, keeps the script"
else notok "without gnuplot (exit $rc)"; fi
finish
