#!/usr/bin/env bash
# grano run --set section.key=value: applied as a scene line would be (the
# same parser and checks), its errors naming the flag, nothing written on
# bad input, the text run stored in the result. TAP.
set -u
. "$(dirname "$0")/tap.sh"
GRANO=$1
SRC=$2
PY=/usr/bin/python3
scene=$SRC/experiments/scenes/box.ini

# Good settings: a new value of a key the file has, and a key it lacks.
if "$GRANO" run "$scene" --until 0.05 --set species.count=100 --set run.observe_every=0.01 \
        --set material.mu=0.3 --out "$tmp/a.h5" -q 2>"$tmp/err" &&
   $PY - "$tmp/a.h5" >"$tmp/err" 2>&1 <<'PY'
import sys, h5py
f = h5py.File(sys.argv[1], "r")
assert f["particles/trajectory/position/value"].shape[1] == 100
assert len(f["observables/ekin_trans/time"]) == 6, f["observables/ekin_trans/time"][:]
text = f["parameters/scene"][()]
text = text.decode() if isinstance(text, bytes) else text
assert "[material]\nmu = 0.3\n" in text and "\n; mu = 0.5\n" in text, text
PY
then ok "--set replaces a key (species.count = 100 grains) and adds one (run.observe_every)"
else notok "--set applied"; fi

# Restart: the same settings continue, none refuses (another scene text).
if "$GRANO" run "$scene" --until 0.1 --set species.count=100 --set run.observe_every=0.01 \
        --set material.mu=0.3 --restart "$tmp/a.ckpt" --out "$tmp/b.h5" -q 2>"$tmp/err"
then ok "restart with the same --set"; else notok "restart with the same --set"; fi
"$GRANO" run "$scene" --until 0.1 --restart "$tmp/a.ckpt" --out "$tmp/c.h5" -q 2>"$tmp/err"
if [ $? = 2 ] && [ ! -e "$tmp/c.h5" ]; then ok "restart without the --set refused"; else notok "restart without --set"; fi

# Bad settings: exit 2, the flag named, nothing written.
bad() {
    local want=$1; shift
    "$GRANO" run "$scene" --until 0.05 --out "$tmp/bad.h5" -q "$@" 2>"$tmp/err"
    local rc=$?
    if [ $rc = 2 ] && [ ! -e "$tmp/bad.h5" ] && grep -qF -- "$want" "$tmp/err"; then
        ok "$* -> $want"
    else
        echo "# exit code $rc, wanted 2 and: $want" >>"$tmp/err"; notok "$*"
    fi
}
bad "grano run: --set material.mu: must be >= 0, got -1" --set material.mu=-1
bad "--set material.muu: unknown key 'muu' in [material]; did you mean 'mu'?" --set material.muu=1
bad "--set materal.mu: unknown section [materal]; did you mean [material]?" --set materal.mu=1
bad "--set domain.gravity: 'abc' is not a number" --set domain.gravity=abc
bad "--set 'mu=0.3': expected SECTION.KEY=VALUE" --set mu=0.3
bad "--set material.mu: given twice" --set material.mu=0.3 --set material.mu=0.2
bad "--set run.contacts: [run] key 'contacts' = yes needs contact networks" --method edmd --set run.contacts=yes
bad "--set dem.dtt: unknown key 'dtt' in [dem]; did you mean 'dt'?" --set dem.dtt=1
finish
