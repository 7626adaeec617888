#!/usr/bin/env bash
# grano compare SCENE.ini: a scene of the user's own on every method that
# models it. The settling bed of 200 disks (restitution 0.9): edmd is the
# reference (the scene gives a restitution), dem, cd and dsmc sweep their
# time steps from their defaults; dem and cd reach 5 % of edmd's potential
# energy, dsmc (a dilute gas, in a bed it flags as dense) does not and its
# validity limits are named; lgca is noted as not modelled. A scene with a
# contact law and no restitution takes dem's finest run as the reference.
# The flags of a user's scene without one, --cases with one, a missing file
# and an observable no method gives exit 2 naming the flag or file. TAP.
set -u
GRANO=$1
SRC=$2
PY=/usr/bin/python3
. "$(dirname "$0")/tap.sh"

refusals compare "--observable temperature:--observable" "--until 3:--until" "$SRC/tests/hard/bed.ini --cases silo:--cases" \
            "$tmp/none.ini:none.ini" "$SRC/tests/hard/bed.ini --observable bogus --out $tmp/b:--observable" \
            "$SRC/tests/hard/bed.ini --reference lgca --out $tmp/b:--reference" \
            "$SRC/tests/hard/bed.ini --until -1:--until"

"$GRANO" compare "$SRC/tests/hard/bed.ini" --until 4 --seeds 1 -j 2 --out "$tmp/bed" --no-progress >"$tmp/log" 2>"$tmp/err"
rc=$?
sed 's/^/# /' "$tmp/log"
check $rc "compare bed.ini runs (exit 0: a scene of one's own reports its checks, does not enforce them)"
grep -q "^# bed: lgca: not modelled: " "$tmp/bed/compare.txt"
check $? "lgca noted as not modelling the bed"

"$GRANO" compare "$SRC/experiments/scenes/compare/column.ini" --methods dem,edmd --until 6 --seeds 1 \
    --out "$tmp/col" --no-progress >"$tmp/log2" 2>"$tmp/err2"
check $? "compare column.ini (kn and gamma_n, no restitution) on dem and edmd"

if $PY -c 'import h5py, numpy' 2>/dev/null; then
    $PY - "$tmp/bed/compare.h5" "$tmp/col/compare.h5" >"$tmp/err" 2>&1 <<'PYEOF'
import sys, h5py, numpy as np
def table(path, name):
    g = h5py.File(path, "r")["cases/" + name]
    return {k: v.asstr()[()] if v.dtype.kind == "O" else v[()] for k, v in g.items()}, g.attrs
t, a = table(sys.argv[1], "bed")
assert a["quantity"] == "epot_grav" and a["reference"] == "edmd", dict(a)
v = list(t["variant"])
assert v.count("dem") == 3 and v.count("cd") == 3 and v.count("dsmc") == 3 and v.count("edmd") == 1, v
assert (t["role"][t["variant"] == "edmd"] == "reference").all()
# dem's knob from its default dt (a fifth of the stable limit) down to a quarter
dt = [float(x) for x in t["knob_value"][t["variant"] == "dem"]]
assert np.allclose([dt[1] / dt[0], dt[2] / dt[0]], [0.5, 0.25]), dt
for m in ("dem", "cd"):
    e = t["rel_error"][t["variant"] == m]
    assert (e < 0.05).all(), (m, e)
d = t["variant"] == "dsmc"
assert (t["outcome"][d] == "beyond").all() and all("limit_dense" in x for x in t["diagnostics"][d]), \
    (t["outcome"][d], t["diagnostics"][d])
t, a = table(sys.argv[2], "column")
assert a["reference"] == "dem-finest", dict(a)
assert list(t["variant"]) == ["edmd", "dem", "dem", "dem-finest"], list(t["variant"])
PYEOF
    check $? "bed: edmd the reference, dem and cd within 5 %, dsmc beyond with limit_dense; column: dem's finest the reference"
else
    ok "compare.h5 check # SKIP no h5py"
fi
echo "1..$n"
[ $fails = 0 ]
