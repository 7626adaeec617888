#!/usr/bin/env bash
# A run's cost watched: a bed of 200 disks settling under gravity on edmd
# (its events per unit time grow as it comes to rest under the tc and
# threshold guards) stops with a diagnostic naming the cause and the keys,
# its last good state kept, within seconds, under the default collapse
# model and under threshold; under collapse = sleep the same bed comes to
# rest (K < 1e-6 K0) with at most 10 times the events per unit time of its
# first; a stop signal during a crawl is honoured between two chunks of
# the advance; dsmc on the bed says it is not a gas. TAP.
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

# the sleep model: the bed comes to rest at a bounded cost (measured 4.9x, K = 0 from t = 15.5)
start=$(date +%s)
timeout 120 "$GRANO" run "$tmp/bed.ini" --method edmd --set edmd.collapse=sleep --out "$tmp/sleep.h5" -q \
    2>"$tmp/err"
rc=$?
took=$(( $(date +%s) - start ))
/usr/bin/python3 - "$tmp/sleep.h5" >"$tmp/bound" 2>>"$tmp/err" <<'PY'
import sys, h5py, numpy as np
o = h5py.File(sys.argv[1], "r")["observables"]
t, ev, K = o["events/time"][:], o["events/value"][:], o["ekin_trans/value"][:]
per_tau = np.diff(np.interp(np.arange(0, int(t[-1]) + 1), t, ev))
print(f"{per_tau.max() / per_tau[0]:.2f} {K[-1] / K[0]:.3g} {t[-1]:g}")
PY
read -r growth krel tend <"$tmp/bound"
if [ $rc = 0 ] && [ "$tend" = 30 ] && [ $took -le 30 ] &&
   /usr/bin/python3 -c "import sys; sys.exit(not ($growth <= 10 and $krel < 1e-6))"; then
    ok "edmd bed, collapse = sleep: at rest (K/K0 = $krel at t = 30), events per unit time at most ${growth}x the first, $took s"
else notok "edmd bed, collapse = sleep (exit $rc, $took s, growth ${growth:-?}x, K/K0 ${krel:-?})"; fi

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
