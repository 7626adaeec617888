#!/usr/bin/env bash
# Bad input to `grano run` (and the other subcommands' refusals of a
# method): exit code 2, a message naming the file, line and key (or the
# flag, the feature or the counter), and no output file written. TAP output.
set -u
GRANO=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0
fails=0

# check_cmd SUBCOMMAND NAME EXPECTED_CODE PATTERN... -- ARGS...
check_cmd() {
    local sub=$1 name=$2 code=$3
    shift 3
    local pats=()
    while [ "$1" != "--" ]; do pats+=("$1"); shift; done
    shift
    n=$((n + 1))
    rm -rf "$tmp/out.h5" "$tmp/out.ckpt" "$tmp/out.h5.xdmf" "$tmp/never"
    "$GRANO" "$sub" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
    local rc=$?
    local ok=1 why=""
    [ "$rc" = "$code" ] || { ok=0; why="exit code $rc, expected $code"; }
    for p in "${pats[@]}"; do
        grep -qF -- "$p" "$tmp/stderr" || { ok=0; why="$why; message lacks '$p'"; }
    done
    if [ "$code" = 2 ] && { [ -e "$tmp/out.h5" ] || [ -e "$tmp/out.ckpt" ] || [ -e "$tmp/never" ]; }; then
        ok=0; why="$why; an output file was written"
    fi
    if [ $ok = 1 ]; then
        echo "ok $n - $name"
    else
        echo "not ok $n - $name: $why"
        sed 's/^/# /' "$tmp/stderr"
        fails=$((fails + 1))
    fi
}
# check NAME EXPECTED_CODE PATTERN... -- ARGS...: grano run
check() { check_cmd run "$@"; }

scene() { # write a scene file from stdin
    cat >"$tmp/$1"
}

scene good.ini <<'INI'
[domain]
width = 10
height = 10
[species]
count = 20
[init]
kind = random
[run]
until = 0.01
INI
scene typo.ini <<'INI'
[domain]
width = 10
height = 10
[species]
count = 20
diamter = 1
INI
scene nan.ini <<'INI'
[domain]
width = 10
height = nan
INI
scene orifice.ini <<'INI'
[domain]
width = 22
height = 30
[species]
count = 10
[silo]
width = 20
height = 20
base = 2
orifice = 25
INI
scene crowded.ini <<'INI'
[domain]
width = 10
height = 10
[species]
count = 200
INI
scene negative.ini <<'INI'
[domain]
width = 10
height = 10
[species]
count = 20
density = -1
INI

scene nograins.ini <<'INI'
[domain]
width = 10
height = 10
[init]
kind = lattice
[run]
until = 0.01
INI
# the methods and what they represent, from the registry (grano methods)
methods_of() { # yes|no: the methods that do (not) represent particles
    "$GRANO" methods | awk -v want="$1" '/^[a-z0-9_]+: /{m=substr($1, 1, length($1) - 1)}
        $1 == "represents:" && ($2 == "particles") == (want == "yes") {print m}'
}
particle_methods=$(methods_of yes)
[ -n "$particle_methods" ] || { echo "not ok 1 - grano methods lists no particle method"; exit 1; }
for m in $particle_methods; do
    check "no grains for $m: the [init] key named" 2 "nograins.ini:5:" "'kind'" "no grains" -- "$tmp/nograins.ini" --method $m --out "$tmp/out.h5"
done
check "missing scene file" 2 "$tmp/none.ini" "cannot read" -- "$tmp/none.ini" --out "$tmp/out.h5"
check "unknown key, nearest suggested" 2 "typo.ini:6:" "diamter" "did you mean 'diameter'" -- "$tmp/typo.ini" --out "$tmp/out.h5"
check "NaN value" 2 "nan.ini:3:" "'height'" "finite" -- "$tmp/nan.ini" --out "$tmp/out.h5"
check "orifice wider than the base" 2 "orifice.ini:10:" "'orifice'" "wider" -- "$tmp/orifice.ini" --out "$tmp/out.h5"
check "more grains than fit" 2 "crowded.ini:5:" "'count'" -- "$tmp/crowded.ini" --out "$tmp/out.h5"
check "negative mass" 2 "negative.ini:6:" "'density'" -- "$tmp/negative.ini" --out "$tmp/out.h5"
check "unknown method" 2 "--method" "'demm'" "did you mean 'dem'" -- "$tmp/good.ini" --method demm --out "$tmp/out.h5"
check "bad --until" 2 "--until" -- "$tmp/good.ini" --until -3 --out "$tmp/out.h5"
check "bad --seed" 2 "--seed" -- "$tmp/good.ini" --seed x --out "$tmp/out.h5"
check "unknown option" 2 "--frobnicate" -- "$tmp/good.ini" --frobnicate
check "missing option value" 2 "--out" -- "$tmp/good.ini" --out

# An existing output is refused without --force, and left untouched.
n=$((n + 1))
echo "precious" >"$tmp/exists.h5"
"$GRANO" run "$tmp/good.ini" --out "$tmp/exists.h5" 2>"$tmp/stderr"
rc=$?
if [ $rc = 2 ] && grep -q -- "--force" "$tmp/stderr" && grep -q "exists.h5" "$tmp/stderr" &&
   [ "$(cat "$tmp/exists.h5")" = precious ]; then
    echo "ok $n - existing output refused without --force"
else
    echo "not ok $n - existing output: exit $rc"; sed 's/^/# /' "$tmp/stderr"; fails=$((fails + 1))
fi

# Backend-specific refusals, when the backend is registered.
if "$GRANO" run --help | grep -q "dem"; then
    scene bigdt.ini <<'INI'
[domain]
width = 10
height = 10
[material]
kn = 1e5
[species]
count = 20
[dem]
dt = 0.01
INI
    check "dem: time step beyond the contact-time limit" 2 "bigdt.ini:9:" "'dt'" -- "$tmp/bigdt.ini" --method dem --out "$tmp/out.h5"
fi

# A method is refused by name when it lacks what an experiment needs.
if "$GRANO" methods | grep -q "edmd"; then
    check_cmd silo-flow "silo-flow: edmd lacks grain walls" 2 "walls made of fixed grains" "'edmd'" -- \
        --method edmd --quick -o "$tmp/never"
    check_cmd silo-start "silo-start: edmd lacks grain walls" 2 "walls made of fixed grains" "'edmd'" -- \
        --method edmd --quick -o "$tmp/never"
    check_cmd course "course: --naive is edmd's" 2 "--naive" "'dem'" -- maxwell --method dem --naive --quick \
        --out "$tmp/never"
fi
check_cmd course "course pressure: dem gives no pair collisions" 2 "'pair_collisions'" "'dem'" -- \
    pressure --method dem --quick --out "$tmp/never"
check_cmd silo-flow "silo-flow: unknown method, nearest suggested" 2 "--method" "'demm'" "did you mean 'dem'" -- \
    --method demm --quick -o "$tmp/never"
check_cmd course "course: unknown method, nearest suggested" 2 "--method" "'edmm'" "did you mean 'edmd'" -- \
    cooling --method edmm --quick --out "$tmp/never"

# A method that writes no particles leaves export nothing to export: said
# so, naming the file and the method (not a --frames message).
for m in $(methods_of no); do
    if "$GRANO" run "$tmp/good.ini" --method "$m" --out "$tmp/lattice-$m.h5" -q 2>"$tmp/stderr"; then
        check_cmd export "export: a $m result holds no trajectory" 2 "lattice-$m.h5 holds no trajectory" \
            "method $m writes fields" -- "$tmp/lattice-$m.h5" --format extxyz --out "$tmp/never"
    else
        n=$((n + 1)); echo "not ok $n - $m runs good.ini"; sed 's/^/# /' "$tmp/stderr"; fails=$((fails + 1))
    fi
done

echo "1..$n"
exit $((fails > 0))
