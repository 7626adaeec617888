#!/usr/bin/env bash
# The reliability behaviours (docs/reliability.md) that are not a refusal (those are rows of
# bad_input.py): each check failed before its fix. TAP output.
set -u
GRANO=$1
SRC=$2
PY=/usr/bin/python3
# the same objects, shapes and values (h5diff passes datasets of different shapes)
SAME="$PY $SRC/tests/experiment/same_h5.py"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cd "$tmp" || exit 1
n=0
fails=0
ok() { n=$((n + 1)); echo "ok $n - $1"; }
notok() { n=$((n + 1)); echo "not ok $n - $1"; fails=$((fails + 1)); [ -f err ] && sed 's/^/# /' err; }
check() { if [ "$2" = 0 ]; then ok "$1"; else notok "$1"; fi; }

cat >rs.ini <<'INI'
[domain]
width = 10
height = 10
gravity = 1
[species]
count = 20
[init]
kind = random
[run]
until = 0.2
output_every = 0.02
checkpoint_every = 0.1
INI

# 1: a periodic strip much longer than its grains hung DEM's cell setup
sed 's/^width = 40/width = 430/' "$SRC/experiments/scenes/vibrated.ini" >vib430.ini
timeout 60 "$GRANO" run vib430.ini --method dem --until 0.01 -o v.h5 -q 2>err
check "1: dem runs vibrated.ini at width 430" $?

# 4: a restart continues its result file: identical to the uninterrupted run
"$GRANO" run rs.ini -o a.h5 -q 2>err &&
    "$GRANO" run rs.ini -o b.h5 -q --until 0.1 2>err &&
    "$GRANO" run rs.ini -o b.h5 -q --restart b.ckpt 2>err &&
    $SAME a.h5 b.h5 >err 2>&1
check "4: restart into the same output keeps the frames before the checkpoint (identical)" $?

# 17: a restart past the end time is refused and changes nothing; one at
# the end time (a run killed while closing) runs nothing and exits 0
sum=$(md5sum b.h5)
"$GRANO" run rs.ini -o b.h5 -q --restart b.ckpt --until 0.1 2>err
rc=$?
[ $rc = 2 ] && grep -q "past the end time" err && [ "$(md5sum b.h5)" = "$sum" ]
check "17: restart past --until refused (exit $rc), result unchanged" $?
"$GRANO" run rs.ini -o b.h5 -q --restart b.ckpt 2>err && $SAME a.h5 b.h5 >>err 2>&1
check "17: restart at the end time: exit 0, result still identical" $?

# 15: a partial checkpoint of a killed run is removed and said
echo partial >c.ckpt.tmp
"$GRANO" run rs.ini -o c.h5 --until 0.02 2>err
rc=$?
[ $rc = 0 ] && [ ! -e c.ckpt.tmp ] && grep -q "removed c.ckpt.tmp" err
check "15: stale c.ckpt.tmp removed and reported" $?

# 16: a full standard output is an error
"$GRANO" methods >/dev/full 2>err
rc=$?
[ $rc = 1 ] && grep -q "standard output" err
check "16: grano methods >/dev/full exits 1 (got $rc)" $?

# 3: observations asked more often than the time step: one per step, none twice
sed 's/^until = 0.2/until = 0.01\nobserve_every = 1e-6/' rs.ini >tiny.ini
timeout 60 "$GRANO" run tiny.ini -o t.h5 -q 2>err &&
    $PY - t.h5 >err 2>&1 <<'PY'
import sys, h5py, numpy as np
t = h5py.File(sys.argv[1], "r")["observables/ekin_trans/time"][:]
assert len(t) > 10 and np.all(np.diff(t) > 0), t[:20]
PY
check "3: observe_every below dt: strictly increasing sample times" $?

# 3: an interval longer than the run is said
sed 's/^until = 0.2/until = 0.02/; s/^output_every = 0.02/output_every = 1e50/' rs.ini >long.ini
"$GRANO" run long.ini -o l.h5 2>err && grep -q "warning: .*long.ini:.*'output_every'.*longer than the run" err
check "3: output_every longer than the run: a warning naming the line" $?

# 14: 20 000 walls load (the key check was quadratic: 44 s)
$PY -c "
s = open('rs.ini').read()
for i in range(20000):
    s += '[wall.w%d]\nfrom = %g 0.1\nto = %g 0.2\n' % (i, i * 4e-4, i * 4e-4 + 1e-5)
open('walls.ini', 'w').write(s)"
timeout 60 "$GRANO" run walls.ini -o w.h5 -q --until 1e-6 2>err
check "14: a scene of 20 000 walls loads and runs a step" $?

# 19: explicit Euler gains energy on a settling bed: stopped with a diagnostic
cat >bed.ini <<'INI'
[domain]
width = 20
height = 20
gravity = 1
[species]
count = 100
[init]
kind = lattice
[dem]
integrator = euler
[run]
until = 30
output_every = 0.5
INI
"$GRANO" run bed.ini -o e.h5 -q 2>err
rc=$?
[ $rc = 1 ] && grep -q "mechanical energy" err && grep -q "last good state saved" err
check "19: dem euler on a settling bed stops (exit $rc) with the energy diagnostic" $?
sed 's/euler/verlet/' bed.ini >bedv.ini
"$GRANO" run bedv.ini -o ev.h5 -q --until 10 2>err
check "19: dem verlet on the same bed runs on" $?

# 2: a full disk (ulimit -f, SIGXFSZ ignored so writes fail as on a full
# disk): exit 1, a clear message, result and checkpoint readable, no .tmp
# (the run would write about 2.3 MB against the limit of 1.5 MB)
sed 's/^until = 0.2/until = 6/; s/^output_every = 0.02/output_every = 0.01/; s/count = 20/count = 60/' rs.ini >fd.ini
mkdir fd
(trap '' XFSZ; ulimit -f 1500; "$GRANO" run fd.ini -o fd/o.h5 -q) 2>err
rc=$?
[ $rc = 1 ] && grep -q "disk is nearly full" err && [ ! -e fd/o.ckpt.tmp ] &&
    $PY - fd/o.h5 fd/o.ckpt >>err 2>&1 <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
pos = f["particles/trajectory/position/value"][:]
assert pos.shape[0] >= 2, pos.shape
h5py.File(sys.argv[2], "r")
PY
check "2: full disk: exit $rc, frames and checkpoint readable" $?

# Settle once, branch many: a restart may change [run] and
# [measure]; a physical change is refused by name unless --branch
sed 's/^until = 0.2/until = 0.1/' rs.ini >short.ini
"$GRANO" run short.ini -o s.h5 -q 2>err &&
    "$GRANO" run rs.ini -o s.h5 --restart s.ckpt 2>err &&
    grep -q "\[run\] until: '0.1' -> '0.2'" err &&
    $SAME a.h5 s.h5 /particles /observables >>err 2>&1
check "branch: a restart with a longer [run] until continues bit for bit and lists the difference" $?
"$GRANO" run short.ini -o s2.h5 -q 2>err
sed 's/^output_every = 0.02/output_every = 0.05/' rs.ini >coarse.ini
"$GRANO" run coarse.ini -o s2.h5 -q --restart s2.ckpt 2>err &&
    $PY - s2.h5 >>err 2>&1 <<'PY'
import sys, h5py, numpy as np
t = h5py.File(sys.argv[1], "r")["particles/trajectory/box/edges/time"][:]
want = [0, 0.02, 0.04, 0.06, 0.08, 0.1, 0.15, 0.2]
assert np.allclose(t, want), t
PY
check "branch: a restart with a new output_every: frames every 0.02 up to the checkpoint, 0.05 after" $?
sed 's/^count = 20/count = 20\n[material]\nmu = 0.3/' rs.ini >mu.ini
sed -i 's/^\[init\]/[init]/' mu.ini
"$GRANO" run mu.ini -o s.h5 -q --restart s.ckpt 2>err
rc=$?
[ $rc = 2 ] && grep -q "'mu'" err && grep -q -- "--branch" err
check "branch: a changed [material] mu is refused by name (exit $rc) without --branch" $?
"$GRANO" run short.ini -o base.h5 -q 2>err &&
    "$GRANO" run mu.ini -o br.h5 -q --restart base.ckpt --branch 2>err &&
    $PY - br.h5 >>err 2>&1 <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
t = f["particles/trajectory/box/edges/time"][:]
assert abs(t[0] - 0.1) < 1e-9 and abs(t[-1] - 0.2) < 1e-9, t
assert "mu = 0.3" in f["parameters/scene"][()].decode()
PY
check "branch: --branch starts a new output at the checkpoint's time with the new mu" $?

echo "1..$n"
exit $((fails > 0))
