#!/usr/bin/env bash
# Fuzz the scene reader and the H5MD/checkpoint reader with clang's
# libFuzzer (ASan and UBSan) for SECONDS each, seeded with the shipped
# scenes and a small result and checkpoint; then replay the regression
# inputs of tests/fuzz/regress/. A crash is a failure, its input kept in
# the build folder to become a regression file. TAP output.
# Usage: run_fuzz.sh SRC GRANO OUTDIR [SECONDS]
set -u
SRC=$1 GRANO=$2 OUT=$3 SECS=${4:-30}
mkdir -p "$OUT"
cd "$OUT" || exit 1
if ! command -v clang >/dev/null; then
    echo "1..0 # SKIP clang not installed (apt-get install clang)"
    exit 0
fi
# the backends' scene sections: the registered methods
sections=$("$GRANO" methods | sed -n 's/^\([a-z0-9_]*\): .*/\1/p' | paste -sd, -)
[ -n "$sections" ] || { echo "not ok 1 - grano methods lists no method"; exit 1; }
flags="-DGR_FUZZ_SECTIONS=\"$sections\" -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined -std=c11
       -D_DEFAULT_SOURCE -D_POSIX_C_SOURCE=200809L -DGRANO_VERSION=\"fuzz\" -I$SRC/common/core
       -I$SRC/common/model -I$SRC/common/io -I$SRC/common/scene
       $(pkg-config --cflags hdf5-serial gsl)"
libs="$(pkg-config --libs hdf5-serial gsl) -lm"
n=0
fails=0
build() { # target sources...
    local t=$1
    shift
    # shellcheck disable=SC2086
    clang $flags -o "$t" "$SRC/tests/fuzz/$t.c" "$@" $libs 2>"$t.build.log"
}
# every file of the scene reader (scene*.c): a new one joins without an edit here
common="$SRC/common/core/err.c $(echo "$SRC"/common/scene/scene*.c)"
h5="$SRC/common/io/h5md.c $SRC/common/io/h5md_read.c $SRC/common/io/h5md_append.c $SRC/common/io/h5md_contacts.c
    $SRC/common/io/h5md_fields.c $SRC/common/io/h5util.c $SRC/common/io/xdmf.c $SRC/common/io/ckpt.c
    $SRC/common/model/particles.c $SRC/common/model/observe.c $SRC/common/model/contacts.c $SRC/common/model/fields.c
    $SRC/common/model/geom.c $SRC/common/core/rng.c"
# shellcheck disable=SC2086
build fuzz_scene $common || { echo "not ok 1 - build fuzz_scene"; sed 's/^/# /' fuzz_scene.build.log; exit 1; }
# shellcheck disable=SC2086
build fuzz_h5md $common $h5 || { echo "not ok 1 - build fuzz_h5md"; sed 's/^/# /' fuzz_h5md.build.log; exit 1; }

rm -rf corpus_scene corpus_h5md crashes
mkdir -p corpus_scene corpus_h5md crashes
cp "$SRC"/experiments/scenes/*.ini corpus_scene/
cat >seed.ini <<'INI'
[domain]
width = 10
height = 10
gravity = 1
[species]
count = 10
[init]
kind = random
[run]
until = 0.02
output_every = 0.01
INI
"$GRANO" run seed.ini -o corpus_h5md/seed.h5 -q --force 2>/dev/null
rm -f corpus_h5md/seed.h5.xdmf
cp corpus_h5md/seed.ckpt corpus_h5md/seed_ckpt.h5 2>/dev/null && rm -f corpus_h5md/seed.ckpt

export LSAN_OPTIONS="suppressions=$SRC/tests/fuzz/lsan.supp"
# Whose fault is a crash input: grano's if a frame in grano's sources comes
# before any frame in the HDF5 library, else the library's (HDF5 1.10 has
# crashes of its own on damaged files, which grano cannot prevent).
whose() { # target input
    ./"$1" "$2" 2>&1 | grep -E '^ *#[0-9]+ ' | grep -E "libhdf5|$SRC/(common|methods|experiments|tests)/[^ ]*\.c:" |
        head -1 | grep -q libhdf5 && echo hdf5 || echo grano
}
fuzz() { # target corpus max_len rss_mb
    n=$((n + 1))
    # Forked workers continue past a crash, so one run finds several.
    ./"$1" -fork=1 -ignore_crashes=1 -ignore_ooms=1 -ignore_timeouts=1 -max_total_time="$SECS" \
        -timeout=10 -rss_limit_mb="$4" -malloc_limit_mb="$4" -max_len="$3" \
        -artifact_prefix=crashes/"$1"- "$2" >"$1.log" 2>&1
    local runs mine=0 lib=0
    runs=$(grep -oE '^#[0-9]+' "$1.log" | tail -1 | tr -d '#')
    for c in crashes/"$1"-*; do
        [ -e "$c" ] || continue
        case $c in *oom-*|*timeout-*|*slow-unit-*) lib=$((lib + 1)); continue ;; esac
        if [ "$(whose "$1" "$c")" = hdf5 ]; then lib=$((lib + 1)); else mine=$((mine + 1)); echo "# grano crash: $c"; fi
    done
    if [ $mine = 0 ]; then
        echo "ok $n - $1: ${SECS} s ${runs:-?} inputs, no crash in grano; $lib in the HDF5 library (inputs in $OUT/crashes)"
    else
        echo "not ok $n - $1: $mine crash(es) in grano (inputs in $OUT/crashes)"
        fails=$((fails + 1))
    fi
}
fuzz fuzz_scene corpus_scene 8192 1024
# HDF5 allocates what a damaged length field says (a variable-length
# string of a gigabyte): allowed up to 3 GB, then counted as the library's.
fuzz fuzz_h5md corpus_h5md 200000 3072

# Inputs that once crashed: replayed every time.
for f in "$SRC"/tests/fuzz/regress/*; do
    [ -e "$f" ] || continue
    n=$((n + 1))
    case $(basename "$f") in scene-*) t=fuzz_scene ;; *) t=fuzz_h5md ;; esac
    if ./"$t" "$f" >/dev/null 2>&1; then echo "ok $n - regression $(basename "$f")"
    else echo "not ok $n - regression $(basename "$f")"; fails=$((fails + 1)); fi
done
echo "1..$n"
exit $((fails > 0))
