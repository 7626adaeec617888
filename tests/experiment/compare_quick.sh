#!/usr/bin/env bash
# grano compare --quick: bad flags exit 2 naming the flag; the quick
# comparison passes its own checks (each method's error does not grow as its
# knob is tightened, beyond the error bars; edmd within each case's stated
# tolerance; every run finished with finite numbers: exit 0 only then);
# compare.h5 holds a typed table per case, read by column name; the pandas
# line of docs/comparison.md reads it; every figure and its gnuplot script
# exist; without gnuplot the data are still written and the exit code is 0;
# the results do not depend on -j. TAP.
set -u
GRANO=$1
PY=/usr/bin/python3
. "$(dirname "$0")/tap.sh"

"$GRANO" compare --help >"$tmp/out" 2>&1 && grep -q "usage: grano compare" "$tmp/out"
check $? "compare --help"
refusals compare "--bogus:--bogus" "-j 0:-j" "--jobs x:-j" "--cases nope:--cases" "--methods nope:--methods" \
            "--cases collision,nope:--cases" "extra:extra" "--out:--out" "--resume --out $tmp/none:--resume" \
            "--resume --force:--resume"

"$GRANO" compare --quick -j 2 --out "$tmp/q" --no-progress >"$tmp/log" 2>"$tmp/err"
rc=$?
sed 's/^/# /' "$tmp/log"
check $rc "compare --quick passes its checks"
# --resume on the finished comparison: every run kept, none redone
mkdir -p "$tmp/r"
cp -r "$tmp/q/parts" "$tmp/r/parts"
"$GRANO" compare --quick --cases collision --resume --out "$tmp/r" --no-progress >"$tmp/res" 2>"$tmp/err"
rc=$?
[ $rc = 0 ] && grep -Eq '^([0-9]+) runs in .* \(\1 reused' "$tmp/res"
check $? "compare --resume keeps every finished run (got $rc: $(grep ' runs in ' "$tmp/res"))"
# grano advise from the quick run's results: every shipped scene gets a
# method and the compare row it relies on (or is the one method that
# models it); a tolerance no row reaches exits 2 naming --tolerance;
# grano run --method auto runs the advice with its setting
src=$(cd "$(dirname "$0")/../.." && pwd)
bad=""
for sc in "$src"/experiments/scenes/*.ini "$src"/experiments/scenes/compare/*.ini "$src"/tests/hard/bed.ini; do
    "$GRANO" advise "$sc" --from "$tmp/q/compare.h5" >"$tmp/adv" 2>>"$tmp/adv.err" &&
        grep -Eq '^(dem|edmd|cd|dsmc|lgca)( with [a-z]+\.[a-z_]+ = [0-9.e-]+)?$' "$tmp/adv" &&
        grep -Eq 'compare row|the only method' "$tmp/adv" || bad="$bad $(basename "$sc")"
done
[ -z "$bad" ]
check $? "grano advise names a method and its compare row on every shipped scene (failed:$bad)"
"$GRANO" advise "$src/experiments/scenes/compare/eos.ini" --from "$tmp/q/compare.h5" --tolerance 1e-6 \
    >/dev/null 2>"$tmp/err"
rc=$?
[ $rc = 2 ] && grep -q -- "--tolerance" "$tmp/err"
check $? "grano advise refuses a tolerance no row reaches, naming --tolerance (got $rc)"
"$GRANO" run "$src/tests/hard/bed.ini" --method auto --from "$tmp/q/compare.h5" --until 0.5 --quiet \
    --out "$tmp/auto.h5" >/dev/null 2>"$tmp/err"
rc=$?
# (which method is cheapest on the column case is a matter of wall time, dem or cd)
[ $rc = 0 ] && grep -Eq -- "--method auto: [a-z]+ with [a-z]+\.[a-z_]+=" "$tmp/err"
check $? "grano run --method auto runs the advice with its setting (got $rc)"
# no holes: every method that models a case's scene has a row in it (a
# method that gains a case's features fails here until it gets one)
grep 'no row in the case table yet' "$tmp/q/compare.txt" >"$tmp/err"
[ $? = 1 ]
check $? "no method models a case and lacks a row in it"
grep -q '^| eos | analytic | ' "$tmp/q/guide.md" && grep -q '^== guide' "$tmp/q/compare.txt"
check $? "guide.md and compare.txt's guide: the cheapest method line per case and error"
for f in compare.h5 compare.txt summary.png summary.gp collision.png collision.gp cooling-dilute.png \
         cooling-dense.png column.png janssen.png eos.png eos.gp vibrated.png silo.png silo.gp silo-widths.png; do
    [ -s "$tmp/q/$f" ]
    check $? "wrote $f"
done

if $PY -c 'import h5py, numpy' 2>/dev/null; then
    $PY - "$tmp/q/compare.h5" >"$tmp/err" 2>&1 <<'PYEOF'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
assert "h5md" not in f and "particles" not in f, "compare.h5 dressed as an H5MD trajectory"
cases = ["collision", "cooling-dilute", "cooling-dense", "column", "janssen", "eos", "vibrated", "silo",
         "silo-widths"]
assert sorted(f["cases"]) == sorted(cases), list(f["cases"])

def table(name):
    """A case's columns by name: strings as str, counts as integers."""
    g = f[name]
    out = {}
    for k, v in g.items():
        assert "unit" in v.attrs and "description" in v.attrs, (name, k, "unit or description missing")
        out[k] = v.asstr()[()] if v.dtype.kind == "O" else v[()]
    return out

for c in cases:
    t = table("cases/" + c)
    n = len(t["method"])
    assert n >= (2 if c == "janssen" else 4 if c != "silo-widths" else 5), (c, n)
    assert t["runs"].dtype.kind == "i" and t["finished"].dtype.kind == "i", (c, "counts not integers")
    lim = t["role"] == "limit"
    assert (t["finished"][~lim] == t["runs"][~lim]).all(), (c, "unfinished runs")
    for k in ("wall_s", "value", "value_sem", "reference", "rel_error", "rel_error_sem", "aux"):
        assert np.isfinite(t[k][~lim]).all(), (c, k, "non-finite")
    assert len(set(t["method"])) >= 2, (c, "fewer than two methods")
    assert set(t["role"]) <= {"sweep", "reference", "bias", "model", "limit", "own"}, (c, set(t["role"]))
    own = t["role"] == "own"
    assert all(a for a in t["against"][own]) and not any(a for a in t["against"][~own]), (c, "against")
    # every row states its outcome against the case's tolerance; a limit
    # row's is a failure or an error not within it, with its reason
    tol = float(f["cases/" + c].attrs["tolerance"])
    assert tol > 0, (c, "no tolerance")
    out = t["outcome"]
    assert set(out) <= {"within", "beyond", "unclear", "failed", "some runs failed", "reference"}, (c, set(out))
    assert all(o != "within" for o in out[lim]), (c, "a limit row within the tolerance", t["variant"][lim])
    fail = out == "failed"
    assert all(m for m in t["message"][fail]), (c, "a failed row without its message")
    ok = (out == "within")
    assert (t["tolerance"][~own] == tol).all() and (t["tolerance"][own] > 0).all(), (c, "row tolerances")
    assert (t["rel_error"][ok] + 2 * t["rel_error_sem"][ok] <= t["tolerance"][ok] + 1e-12).all(), \
        (c, "within, beyond tol")
# the rows that fill what were holes: each method that models a case has one,
# and where it meets its limit, the row says how
t = table("cases/janssen")
e = t["variant"] == "edmd"
assert list(t["outcome"][e]) == ["failed"] * 1 and "cost grew" in t["message"][e][0], \
    ("janssen edmd: collapse stopped by the cost bound", t["outcome"][e], t["message"][e])
t = table("cases/column")
e = t["variant"] == "edmd"
assert t["rel_error"][e][0] > 0.9 and t["role"][e][0] == "limit", ("column edmd: no force at rest", t["value"][e])
t = table("cases/collision")
d = t["variant"] == "dsmc"
assert (t["outcome"][d] == "beyond").all() and "ppc_min" in t["diagnostics"][d][0], \
    ("collision dsmc: beyond, its diagnostic", t["outcome"][d], t["diagnostics"][d])
for c, m in (("cooling-dilute", "cd"), ("cooling-dense", "cd"), ("eos", "cd"), ("vibrated", "cd"),
             ("silo-widths", "cd"), ("silo-widths", "edmd"), ("column", "dsmc"), ("column", "lgca"),
             ("cooling-dilute", "lgca")):
    assert m in set(table("cases/" + c)["method"]), (c, m, "no row")
# the lattice gas against its own model: the floor carries a fraction of
# the nominal weight (the grains' answer is 1), its mean-field hydrostatics
# within 1 % (0.4 % at the coarsest spacing); its moving population cools
# as the Boltzmann map of its table says, within 1 % (0.1 %)
for c, lo, hi in (("column", 0.3, 0.7), ("cooling-dilute", 0.3, 0.5)):
    t = table("cases/" + c)
    g = t["method"] == "lgca"
    assert (t["role"][g] == "own").all() and t["outcome"][g][-1] == "within", (c, t["outcome"][g])
    assert (t["rel_error"][g] < 0.01).all(), (c, "lgca against its own model", t["rel_error"][g])
    assert ((t["reference"][g] > lo) & (t["reference"][g] < hi)).all(), (c, "lgca's own answer", t["reference"][g])
# knob values are kept as written: dsmc-weight's "count:weight" pairs
t = table("cases/cooling-dilute")
w = t["knob_value"][t["variant"] == "dsmc-weight"]
assert list(w) == ["64:4", "256:1"], ("dsmc-weight's knob values", w)
assert f["cases/cooling-dilute/value"].attrs["unit"] == "1" and f["cases/collision/wall_s"].attrs["unit"] == "s"
# the flow rate's shape Q(4 d)/Q(6 d) (value) and Q(8 d)/Q(6 d) (aux):
# every row, lgca's three resolutions included, has Q(4) < Q(6) < Q(8);
# lgca (on its own scene) settles on a flow nearly linear in D (2/3,
# within 0.05 at its two finest resolutions; measured 0.645-0.670), dem's
# long run on a steeper one (Beverloo's 0.375): below lgca's by 0.1 or more
# (measured 0.45 in --quick's one short run, 0.36 in the full one)
# (cd at its quick setting, tol 1e-2, jams at 4 d: Q(4) = 0, its outcome)
t = table("cases/silo-widths")
flows = t["method"] != "cd"
v, aux = t["value"][flows], t["aux"][flows]
assert (v > 0).all() and (v < 1).all() and (aux > 1).all(), ("Q(D) not increasing", v, aux)
assert (t["outcome"][~flows] == "beyond").all(), ("cd's jam at 4 d", t["value"][~flows], t["outcome"][~flows])
lg = t["value"][t["method"] == "lgca"]
assert len(lg) == 3, ("lgca rows", t["method"])
assert list(t["knob_value"][t["method"] == "lgca"]) == ["0.5:0.05", "0.25:0.025", "0.125:0.0125"], t["knob_value"]
assert (abs(lg[1:] - 2 / 3) < 0.05).all(), ("lgca's Q(4)/Q(6)", lg)
ref = t["value"][t["role"] == "reference"]
assert len(ref) == 1 and ref[0] < lg[-1] - 0.1, ("dem-long's Q(4)/Q(6)", ref, lg[-1])
# the vibrated bed's profiles against edmd's long run: finite, and dem's
# density profile within 10 % (relative L2; measured 0.026-0.028)
e = table("profiles/vibrated/errors")
for k in ("density_l2", "density_l2_sem", "density_max", "temperature_l2", "temperature_l2_sem"):
    assert np.isfinite(e[k]).all(), ("non-finite profile error", k)
dem = e["density_l2"][e["variant"] == "dem"]
assert len(dem) and (dem < 0.1).all(), ("dem's density profile", dem)
b = table("profiles/vibrated/bins")
assert len(b["height"]) == 24 * len(e["variant"]), len(b["height"])
# the cost to reach 1, 5 and 10 %: three targets per line of every case; a
# line that reaches 1 % reaches 5 and 10 %, and one that reaches a target
# with its errors raised by their bars reaches it with them as measured
for c in cases:
    r = table("reach/" + c)
    assert set(np.round(r["target"], 3)) == {0.01, 0.05, 0.1}, (c, "targets", r["target"])
    for v in set(r["variant"]):
        x = {round(t, 3): (w, hi) for t, w, hi, var in zip(r["target"], r["wall_s"], r["wall_s_hi"], r["variant"])
             if var == v}
        reached = [np.isfinite(x[t][0]) for t in (0.01, 0.05, 0.1)]
        assert reached == sorted(reached), (c, v, "a tighter error reached, a looser not", reached)
        assert all(np.isfinite(x[t][0]) or not np.isfinite(x[t][1]) for t in x), (c, v, "hi without value")
PYEOF
    check $? "compare.h5: a typed table per case read by name, two methods or more each, knob values as written; vibrated profiles; silo-widths: Q(D) grows, lgca settles near linear, dem steeper"
else
    ok "compare.h5 check # SKIP no h5py"
fi

# docs/comparison.md's one line that reads a case into pandas, run as written
docline=$(grep -m1 '^ */usr/bin/python3 -c "import h5py, pandas' "$(dirname "$0")/../../docs/comparison.md" | sed 's/^ *//')
if [ -z "$docline" ]; then
    notok "docs/comparison.md shows the pandas one-liner"
elif $PY -c 'import pandas' 2>/dev/null; then
    (cd "$tmp/q" && bash -c "$docline") >"$tmp/pd" 2>"$tmp/err" &&
        grep -q "dem-gear" "$tmp/pd" && grep -q "method" "$tmp/pd" && grep -q "analytic" "$tmp/pd" &&
        grep -q "^10 " "$tmp/pd" && ! grep -q "^11 " "$tmp/pd"
    check $? "docs/comparison.md's pandas line reads cases/collision (rows 0-10, named columns; pandas wraps or elides columns by terminal)"
else
    ok "pandas one-liner # SKIP /usr/bin/python3 lacks pandas (./grano.sh deps installs python3-pandas)"
fi

# without gnuplot on PATH the data are written, the figures are not, and
# the study says so and exits 0 (the runs are reused from the quick run)
mkdir -p "$tmp/nognu" "$tmp/ng"
cp -r "$tmp/q/parts" "$tmp/ng/parts"
PATH=$tmp/nognu "$GRANO" compare --quick --cases collision --out "$tmp/ng" --no-progress >"$tmp/log" 2>"$tmp/err"
rc=$?
[ $rc = 0 ] && [ -s "$tmp/ng/compare.h5" ] && [ -s "$tmp/ng/compare.txt" ] && [ ! -e "$tmp/ng/collision.png" ] &&
    grep -q "gnuplot is not on PATH" "$tmp/err"
check $? "compare without gnuplot: exit 0 (got $rc), compare.h5 and compare.txt written, no figure, says why"

# the same runs one at a time give the same numbers (wall times aside: the
# 5th column, and the costs to reach an error, indented, and the guide)
"$GRANO" compare --quick -j 1 --cases collision,column --out "$tmp/j1" --no-progress >/dev/null 2>"$tmp/err"
check $? "compare --quick -j 1 on two cases"
grep -v "^#" "$tmp/q/compare.txt" | awk '/^== (collision|column)/{p=1} /^== (cooling|janssen|eos|guide)/{p=0} p' |
    awk '!/^  /{$5=""; print}' >"$tmp/a"
grep -v "^#" "$tmp/j1/compare.txt" | awk '/^== guide/{exit} !/^  /{$5=""; print}' >"$tmp/b"
diff <(grep -v "^ *$" "$tmp/a") <(grep -v "^ *$" "$tmp/b") >"$tmp/err"
check $? "results independent of -j"

# every figure's axes fit its data (the scripts replayed by gnuplot)
if command -v gnuplot >/dev/null && [ -x /usr/bin/python3 ]; then
    /usr/bin/python3 "$(dirname "$0")/figure_axes.py" "$tmp/q" >"$tmp/err" 2>&1
    check $? "compare's figures: no axis five times wider than its data"
fi

echo "1..$n"
[ $fails = 0 ]
