#!/usr/bin/env bash
# grano silo-flow over two MPI ranks gives the serial run's numbers bit for
# bit: every unit (filling of a realisation, then each orifice branched
# from it) draws from its own seeds whatever rank runs it, and rank 0 alone
# writes the report from every rank's parts. TAP.
set -u
GRANO=$1
MPIRUN=$2
# shellcheck source=tap.sh
. "$(dirname "$0")/tap.sh"

args="silo-flow --quick --orifices 6.24,10,14 --blocks 4 --realisations 2 -q"
# shellcheck disable=SC2086
"$GRANO" $args -o "$tmp/serial" >"$tmp/out" 2>"$tmp/err"
check $? "serial quick sweep runs"
# as root mpirun refuses to start without --allow-run-as-root; two ranks
# on a loaded or one-core machine need --oversubscribe
# shellcheck disable=SC2086
"$MPIRUN" --allow-run-as-root --oversubscribe -n 2 "$GRANO" $args -o "$tmp/mpi" >"$tmp/out" 2>"$tmp/err"
check $? "mpirun -n 2 quick sweep runs"
same=0
for f in flow.dat fits.dat reduced_flow.dat pdf_fluctuations.dat; do
    cmp -s "$tmp/serial/$f" "$tmp/mpi/$f" || { same=1; echo "# $f differs" >"$tmp/err"; }
done
check $same "two ranks give the serial tables bit for bit"
# and the same HDF5 tables, column by column (read by name)
/usr/bin/python3 - "$tmp/serial/silo-flow.h5" "$tmp/mpi/silo-flow.h5" >"$tmp/err" 2>&1 <<'PY'
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r")
for t in ("flow", "fits", "pdf_fluctuations", "pdf_fluctuation_stats", "blocks"):
    assert list(a[t]) == list(b[t]), (t, list(a[t]), list(b[t]))
    for k in a[t]:
        x, y = a[t][k][()], b[t][k][()]
        same = (x == y).all() if x.dtype.kind in "OSi" else np.array_equal(x, y, equal_nan=True)
        assert same, (t, k, x, y)
assert list(a["flow/D"][()]) == [6.24, 10, 14] and (a["blocks/grains"][()] >= 0).all()
assert a["blocks/grains"].dtype.kind == "i" and len(a["blocks/grains"]) == 3 * 2 * 4
PY
check $? "two ranks give the serial silo-flow.h5 tables, every column by name"
# every unit's part exists once, written by one of the ranks
np=$(find "$tmp/mpi/parts" -name '*.part' | wc -l)
[ "$np" = 8 ]
check $? "two fillings and six orifice parts in the shared directory (found $np)"
finish
