#!/usr/bin/env bash
# A run's cost watched: a bed of 200 disks settling under gravity on edmd
# (tests/hard/bed.ini: its events per unit time grow as it comes to rest
# under the tc and threshold guards) stops with a diagnostic naming the
# cause and the keys, its last good state kept, within seconds, under
# collapse = tc and threshold; a stop signal during a crawl is honoured
# between two chunks of the advance. The same bed at rest under the default
# (collapse = sleep), and on dsmc, is tests/hard's. TAP.
set -u
. "$(dirname "$0")/tap.sh"
GRANO=$1
cp "$(dirname "$0")/../hard/bed.ini" "$tmp/bed.ini"
for model in tc threshold; do
    start=$(date +%s)
    timeout 120 "$GRANO" run "$tmp/bed.ini" --method edmd --set edmd.collapse=$model --out "$tmp/$model.h5" -q \
        2>"$tmp/err"
    rc=$?
    took=$(( $(date +%s) - start ))
    if [ $rc = 1 ] && grep -q "the cost grew past its bound at t = " "$tmp/err" &&
       grep -q "\[edmd\] collapse chooses the inelastic-collapse model; \[run\] max_cost_growth sets this bound" "$tmp/err" &&
       grep -q "last good state saved in $tmp/$model.ckpt" "$tmp/err" && "$GRANO" info "$tmp/$model.ckpt" >/dev/null 2>&1 &&
       [ $took -le 60 ]; then
        ok "edmd bed, collapse = $model: stopped in $took s, the cost's growth named, the state kept"
    else notok "edmd bed, collapse = $model (exit $rc, $took s)"; fi
done

# without the bound the bed crawls; SIGTERM stops it at once
"$GRANO" run "$tmp/bed.ini" --method edmd --set edmd.collapse=threshold --set run.max_cost_growth=0 \
    --out "$tmp/crawl.h5" -q 2>"$tmp/err" & pid=$!
sleep 8
kill -TERM $pid
start=$(date +%s)
wait $pid
rc=$?
took=$(( $(date +%s) - start ))
if [ $rc = 143 ] && [ $took -le 2 ] && grep -q "stopped by SIGTERM at t = " "$tmp/err"; then
    ok "SIGTERM during a crawl between samples: exit 143 within $took s, the stop said"
else notok "SIGTERM during a crawl (exit $rc, $took s)"; fi
finish
