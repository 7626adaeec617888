#!/usr/bin/env bash
# Stops and records: a run stopped by SIGTERM says where it stopped, keeps
# a checkpoint from which a restart ends bit for bit as the uninterrupted
# run; a checkpoint's step is the result's step at the same time, on every
# method with particles; a stop signal to a sweep's parent ends its workers
# (and so does SIGKILL), and the sweep resumes from its finished parts. TAP.
set -u
. "$(dirname "$0")/tap.sh"
GRANO=$1
SRC=$2
PY=/usr/bin/python3
box=$SRC/experiments/scenes/box.ini
gas=$SRC/experiments/scenes/compare/cooling-dilute.ini

# a process computing (a zombie has ended, its reaper not yet come)
alive() { local s; s=$(ps -o stat= -p "$1" 2>/dev/null) && [ -n "$s" ] && [ "${s#Z}" = "$s" ]; }

# --- a run stopped by SIGTERM
"$GRANO" run "$box" --method dem --until 30 --out "$tmp/full.h5" -q 2>"$tmp/err"
check $? "the uninterrupted run"
"$GRANO" run "$box" --method dem --until 30 --out "$tmp/part.h5" -q 2>"$tmp/err" & pid=$!
# the whole run takes about 7 s alone on 2 cores: stop it in its course
sleep 2
kill -TERM $pid
wait $pid
rc=$?
if [ $rc = 143 ] && grep -q "stopped by SIGTERM at t = " "$tmp/err" && grep -q "holds .* frames up to t = " "$tmp/err" &&
   grep -q "the checkpoint $tmp/part.ckpt holds the state" "$tmp/err"; then
    ok "SIGTERM: exit 143, the time reached, the frames and the checkpoint said"
else notok "SIGTERM to a run (exit $rc)"; fi
"$GRANO" run "$box" --method dem --until 30 --out "$tmp/part.h5" --restart "$tmp/part.ckpt" -q 2>"$tmp/err"
check $? "the restart from the stop's checkpoint runs"
$PY "$(dirname "$0")/same_h5.py" "$tmp/full.h5" "$tmp/part.h5" /particles /observables >"$tmp/err" 2>&1
check $? "stopped and restarted: positions and observables identical to the uninterrupted run"

# --- the checkpoint's step is the result's, on every method with particles
for m in dem edmd cd dsmc; do
    scene=$box; [ $m = dsmc ] && scene=$gas
    "$GRANO" run "$scene" --method $m --until 1 --out "$tmp/s-$m.h5" -q 2>"$tmp/err"
    $PY - "$tmp/s-$m.h5" "$tmp/s-$m.ckpt" >"$tmp/err" 2>&1 <<'PYEOF'
import sys, h5py
def last(path):
    with h5py.File(path, "r") as f:
        g = next(iter(f["particles"].values()))["position"]
        return int(g["step"][-1]), float(g["time"][-1])
(sr, tr), (sc, tc) = last(sys.argv[1]), last(sys.argv[2])
print("result step %d at t = %g, checkpoint step %d at t = %g" % (sr, tr, sc, tc))
sys.exit(0 if sr == sc and abs(tr - tc) < 1e-12 and sr > 0 else 1)
PYEOF
    check $? "$m: the checkpoint's step equals the result's at the same time"
done

# --- sweeps: a stop signal to the parent ends the workers; the sweep resumes
S=$tmp/sweep
"$GRANO" silo-start --quick --jobs 2 -o "$S" -q >/dev/null 2>"$tmp/err" & pid=$!
for i in $(seq 1 100); do [ -s "$S/parts/fill-r00.part" ] && break; sleep 0.2; done
sleep 1
workers=$(pgrep -P $pid | tr '\n' ' ')
kill -TERM $pid
wait $pid
rc=$?
sleep 1
left=""
for w in $workers; do alive "$w" && left="$left $w"; done
if [ $rc = 143 ] && [ -n "$workers" ] && [ -z "$left" ] && grep -q "stopped by SIGTERM" "$tmp/err" &&
   grep -q "the same command resumes the sweep" "$tmp/err"; then
    ok "SIGTERM to silo-start -j 2: exit 143, its workers ($workers) gone a second later, resuming said"
else notok "SIGTERM to a sweep (exit $rc, workers '$workers', left '$left')"; fi
n_parts=$(find "$S/parts" -name '*.part' | wc -l)
"$GRANO" silo-start --quick --jobs 2 -o "$S" -q >/dev/null 2>"$tmp/err"
rc=$?
if [ $rc = 0 ] && [ "$n_parts" -ge 1 ] && [ -s "$S/silo-start.h5" ]; then
    ok "the same command resumes from the $n_parts finished parts and ends"
else notok "the sweep resumes (exit $rc, $n_parts parts)"; fi

# SIGKILL cannot be caught: the workers die with their parent all the same
F=$tmp/flow
"$GRANO" silo-flow --quick --jobs 2 -o "$F" -q >/dev/null 2>&1 & pid=$!
for i in $(seq 1 50); do [ -n "$(pgrep -P $pid)" ] && break; sleep 0.1; done
workers=$(pgrep -P $pid | tr '\n' ' ')
kill -KILL $pid
wait $pid 2>/dev/null
sleep 1
left=""
for w in $workers; do alive "$w" && left="$left $w"; done
if [ -n "$workers" ] && [ -z "$left" ]; then ok "SIGKILL to silo-flow -j 2: its workers ($workers) gone a second later"
else notok "SIGKILL to a sweep (workers '$workers', left '$left')"; fi
finish
