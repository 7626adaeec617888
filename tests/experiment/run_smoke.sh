#!/usr/bin/env bash
# grano run end to end: writes H5MD that h5py reads, restarts from its
# checkpoint bit for bit, and a killed run leaves a readable file. TAP.
set -u
GRANO=$1
SRC=$2
PY=/usr/bin/python3
. "$(dirname "$0")/tap.sh"
if ! $PY -c 'import h5py, numpy' 2>/dev/null; then
    echo "1..0 # SKIP /usr/bin/python3 lacks h5py"
    exit 0
fi
scene=$SRC/experiments/scenes/box.ini

if "$GRANO" run "$scene" --method dem --until 0.4 --out "$tmp/a.h5" -q 2>"$tmp/err"; then
    ok "run box.ini to t = 0.4"
else
    notok "run box.ini to t = 0.4"
fi

if $PY - "$tmp/a.h5" "$scene" >"$tmp/err" 2>&1 <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
pos = f["particles/trajectory/position/value"]
assert pos.shape[1:] == (400, 2), pos.shape
t = f["particles/trajectory/position/time"][:]
assert pos.shape[0] == len(t) >= 2 and abs(t[-1] - 0.4) < 1e-9, t
assert np.all(np.isfinite(pos[:]))
ek = f["observables/ekin_trans/value"][:]
assert len(ek) >= 5 and np.all(ek > 0)
text = f["parameters/scene"][()]
text = text.decode() if isinstance(text, bytes) else text
assert text == open(sys.argv[2]).read()
assert f["parameters/method"][()] in (b"dem", "dem")
PY
then ok "h5py reads the trajectory, observables and scene text"; else notok "h5py check"; fi

# Restart: a to 0.4, then on to 0.8 from its checkpoint, equals one run to 0.8.
"$GRANO" run "$scene" --method dem --until 0.8 --restart "$tmp/a.ckpt" --out "$tmp/b.h5" -q 2>"$tmp/err" &&
"$GRANO" run "$scene" --method dem --until 0.8 --out "$tmp/c.h5" -q 2>>"$tmp/err"
if [ $? = 0 ] && $PY - "$tmp/b.h5" "$tmp/c.h5" >>"$tmp/err" 2>&1 <<'PY'
import sys, h5py, numpy as np
b = h5py.File(sys.argv[1], "r"); c = h5py.File(sys.argv[2], "r")
for el in ("position", "velocity"):
    vb = b[f"particles/trajectory/{el}/value"][-1]
    vc = c[f"particles/trajectory/{el}/value"][-1]
    assert np.array_equal(vb, vc), f"{el} differs: max {np.max(np.abs(vb - vc))}"
assert b["particles/trajectory/position/time"][-1] == c["particles/trajectory/position/time"][-1]
PY
then ok "restart from the checkpoint continues bit for bit"; else notok "restart bit for bit"; fi

# A restart against another scene is refused.
sed 's/count = 400/count = 399/' "$scene" >"$tmp/other.ini"
"$GRANO" run "$tmp/other.ini" --method dem --restart "$tmp/a.ckpt" --out "$tmp/d.h5" -q 2>"$tmp/err"
if [ $? = 2 ] && grep -q "physical parameter differs" "$tmp/err" && [ ! -e "$tmp/d.h5" ]; then
    ok "restart with another scene refused"; else notok "restart with another scene refused"; fi

# Killed mid-run: the file is readable up to its last flush, in the read
# mode of a file being written (HDF5's SWMR reader), during the run and after.
"$GRANO" run "$scene" --method dem --until 1000 --out "$tmp/k.h5" -q 2>/dev/null &
pid=$!
for _ in $(seq 1 100); do
    sleep 0.2
    $PY -c "import h5py,sys; f=h5py.File('$tmp/k.h5','r',swmr=True); sys.exit(0 if f['particles/trajectory/position/value'].shape[0] >= 2 else 1)" 2>/dev/null && break
done
kill -9 $pid 2>/dev/null; wait $pid 2>/dev/null
if $PY - "$tmp/k.h5" >"$tmp/err" 2>&1 <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r", swmr=True)
p = f["particles/trajectory/position/value"]
assert p.shape[0] >= 2 and np.all(np.isfinite(p[:]))
PY
then ok "a killed run leaves a readable file"; else notok "killed run readable"; fi
# The shipped cd scene: a settling pile with its contact network.
if "$GRANO" run "$SRC/experiments/scenes/pile.ini" --method cd --until 3 --out "$tmp/pile.h5" -q 2>"$tmp/err" &&
   $PY - "$tmp/pile.h5" >>"$tmp/err" 2>&1 <<'PY'
import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], "r")
c = f["contacts"]
n = c["count"][:]
assert len(n) == len(f["particles/trajectory/position/time"]) and n[-1] > 0
ids = set(f["particles/trajectory/id"][:].tolist())
start = int(n[:-1].sum())
i, j = c["i"][start:], c["j"][start:]
assert set(i.tolist()) <= ids and all(x < 0 or x in ids for x in j.tolist())
assert np.all(np.isfinite(c["force"][:])) and np.all(c["force"][start:, 0] >= 0)
PY
then ok "pile.ini on cd writes its contact network"; else notok "pile.ini on cd: $(cat "$tmp/err")"; fi
echo "1..$n"
exit $((fails > 0))
