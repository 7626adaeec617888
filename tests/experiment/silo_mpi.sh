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
"$GRANO" $args -o "$tmp/serial" 2>"$tmp/err"
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
# every unit's part exists once, written by one of the ranks
np=$(find "$tmp/mpi/parts" -name '*.part' | wc -l)
[ "$np" = 8 ]
check $? "two fillings and six orifice parts in the shared directory (found $np)"
finish
