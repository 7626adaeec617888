#!/usr/bin/env bash
# grano run's thermo lines off a terminal: a header, then one line per
# [run] thermo_every of simulated time (step, time, energies, temperature,
# outflow, throughput) whose energies are the ones written to the result;
# none with thermo_every = 0, nothing at all with --quiet, and none on a
# terminal (the progress line is there instead). TAP.
set -u
. "$(dirname "$0")/tap.sh"
GRANO=$1
SRC=$2
PY=/usr/bin/python3
scene=$SRC/experiments/scenes/box.ini

# box.ini writes a frame every 0.5: thermo_every defaults to it.
"$GRANO" run "$scene" --until 1 --out "$tmp/a.h5" 2>"$tmp/log" >/dev/null
if $PY - "$tmp/log" "$tmp/a.h5" 0 0.5 1 >"$tmp/err" 2>&1 <<'PY'
import sys, h5py, numpy as np
# what grano run says besides (the parameters it derived) is not thermo
lines = [l for l in open(sys.argv[1]).read().splitlines() if not l.startswith("grano run:")]
head = lines[0].split()
assert head == ["Step", "Time", "KinEng", "PotEng", "Temp", "Outflow", "Steps/s"], lines[0]
rows = [l.split() for l in lines[1:] if not l.startswith("grano run:")]
assert all(len(r) == 7 for r in rows), rows
rows = np.array(rows, dtype=float)
want = np.array([float(x) for x in sys.argv[3:]])
assert np.allclose(rows[:, 1], want), rows[:, 1]
f = h5py.File(sys.argv[2], "r")
t = f["observables/ekin_trans/time"][:]
ek = f["observables/ekin_trans/value"][:] + f["observables/ekin_rot/value"][:]
steps = f["observables/ekin_trans/step"][:]
for r in rows:
    k = np.argmin(abs(t - r[1]))
    assert abs(t[k] - r[1]) < 1e-9 and steps[k] == r[0], (r, t[k], steps[k])
    assert abs(r[2] / ek[k] - 1) < 1e-5, (r[2], ek[k])
assert np.all(np.diff(rows[:, 0]) > 0) and np.all(rows[1:, 6] > 0), rows
PY
then ok "thermo lines every output_every, energies as in the result"; else notok "thermo lines"; fi

"$GRANO" run "$scene" --until 1 --set run.thermo_every=0.2 --out "$tmp/b.h5" 2>"$tmp/log" >/dev/null
if $PY - "$tmp/log" "$tmp/b.h5" 0 0.2 0.4 0.6 0.8 1 >"$tmp/err" 2>&1 <<'PY'
import sys, numpy as np
lines = [l for l in open(sys.argv[1]).read().splitlines() if not l.startswith("grano run:")][1:]
t = np.array([float(l.split()[1]) for l in lines])
want = np.array([float(x) for x in sys.argv[3:]])
assert len(t) == len(want) and np.allclose(t, want), t
PY
then ok "[run] thermo_every = 0.2: six lines"; else notok "thermo_every 0.2"; fi

"$GRANO" run "$scene" --until 0.5 --set run.thermo_every=0 --out "$tmp/c.h5" 2>"$tmp/log" >/dev/null
if [ $? = 0 ] && ! grep -q "Step" "$tmp/log"; then ok "thermo_every = 0: no thermo lines"; else notok "thermo_every = 0"; fi

"$GRANO" run "$scene" --until 0.5 --quiet --out "$tmp/d.h5" >"$tmp/log" 2>&1
if [ $? = 0 ] && [ ! -s "$tmp/log" ]; then ok "--quiet prints nothing"; else notok "--quiet"; fi

if command -v script >/dev/null; then
    script -qec "'$GRANO' run '$scene' --until 0.5 --out '$tmp/e.h5'" /dev/null >"$tmp/log" 2>&1
    if [ $? = 0 ] && ! grep -q "Step" "$tmp/log"; then ok "on a terminal: no thermo lines"; else notok "terminal"; fi
fi
finish
