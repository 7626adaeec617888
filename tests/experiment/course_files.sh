#!/usr/bin/env bash
# grano course's files as a reader meets them: grano info on a course result
# prints its tables (no box of nan), and maxwell.dat holds its two tables
# as gnuplot's data sets (index 0 and 1, two blank lines between). TAP.
set -u
. "$(dirname "$0")/tap.sh"
GRANO=$1

if ! "$GRANO" course maxwell --quick --out "$tmp/c" >"$tmp/err" 2>&1; then
    notok "grano course maxwell --quick"; finish
fi
"$GRANO" info "$tmp/c/maxwell.h5" >"$tmp/info" 2>"$tmp/err"
rc=$?
cp "$tmp/info" "$tmp/err"
if [ $rc = 0 ] && ! grep -qi nan "$tmp/info" && grep -q "^trajectory   none" "$tmp/info" &&
   grep -q "maxwell/distance \[5 x 5\]: distance to Maxwell" "$tmp/info" &&
   grep -q "columns: collisions_per_grain, ks, chi2, dof, pvalue" "$tmp/info" &&
   [ "$(grep -cE '^ +(0.5|1|2|3|10) ' "$tmp/info")" = 5 ]; then
    ok "grano info on a course result: its tables, described, no nan"
else notok "grano info on a course result"; fi

if command -v gnuplot >/dev/null; then
    recs=$(cd "$tmp/c" && gnuplot -e "stats 'maxwell.dat' index 0 u 1 nooutput; a = STATS_records; stats 'maxwell.dat' index 1 u 7 nooutput; print a, STATS_records, STATS_blocks" 2>&1)
    echo "$recs" >"$tmp/err"
    if [ "$recs" = "5 24 1" ]; then ok "maxwell.dat: gnuplot reads 5 rows at index 0, 24 at index 1"
    else notok "maxwell.dat data sets for gnuplot (got '$recs')"; fi
fi
finish
