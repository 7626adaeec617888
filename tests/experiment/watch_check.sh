#!/usr/bin/env bash
# A run's cost watched: a bed of 200 disks settling under gravity on edmd
# (its events per unit time grow as it comes to rest) stops with a
# diagnostic naming the cause and the keys, its last good state kept,
# within seconds, under the default collapse model and under threshold;
# a stop signal during such a crawl is honoured between two chunks of the
# advance; dsmc on the bed says it is not a gas. TAP.
set -u
. "$(dirname "$0")/tap.sh"
GRANO=$1
cat >"$tmp/bed.ini" <<'INI'
[scene]
name = bed
seed = 1
[domain]
width = 20
height = 40
gravity = 1
[material]
restitution = 0.9
[species]
count = 200
[init]
kind = lattice
velocity = gaussian
v0 = 1
[run]
until = 30
output_every = 1
observe_every = 0.5
INI
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

# dsmc on the same bed: not a gas, said with the region, refused under strict
"$GRANO" run "$tmp/bed.ini" --method dsmc --until 2 --out "$tmp/dsmc.h5" -q 2>"$tmp/err"
rc=$?
if [ $rc = 0 ] && grep -q "validity limit limit_dense broken at t = .*: the packing fraction reaches 0\.[5-9][0-9]* in x .* d, above 0.5: not a gas" "$tmp/err"; then
    ok "dsmc on the bed: 'not a gas' said with the region and the packing fraction"
else notok "dsmc on the bed says it is not a gas (exit $rc)"; fi
# (the bed breaks the cells' limits too, which strict meets first)
"$GRANO" run "$tmp/bed.ini" --method dsmc --until 2 --set run.strict=yes --out "$tmp/dsmc2.h5" -q 2>"$tmp/err"
rc=$?
if [ $rc = 1 ] && grep -q "validity limit limit_.* broken at t = 0.5" "$tmp/err" && grep -q "stopped" "$tmp/err"; then
    ok "dsmc on the bed under [run] strict = yes: refused at the first sample, exit 1"
else notok "dsmc on the bed under strict (exit $rc)"; fi

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
