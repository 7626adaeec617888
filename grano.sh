#!/usr/bin/env bash
# grano.sh: the one entry point. deps | build | demo | test | bench | run | python ...
# Each command sets up what it needs first, so each works alone on a fresh
# Debian 12 machine.
set -euo pipefail
cd "$(dirname "$0")"

BUILD=build
SAN=build-san
PACKAGES=(meson ninja-build pkg-config gcc libc6-dev libgsl-dev libsundials-dev libhdf5-dev
          hdf5-tools libcmocka-dev gnuplot-nox python3-h5py python3-numpy
          libsiconos-numerics-dev librandom123-dev python3-ase python3-pandas python3-matplotlib
          python3-pytest)
# optional, installed by `deps --optional` only: lammps (lmp) for
# `grano bench dem --peer lammps` and `grano silo-flow --peer lammps`;
# ffmpeg for `grano movie` to MP4 (a GIF needs only gnuplot)
OPTIONAL=(lammps ffmpeg)

say() { printf 'grano.sh: %s\n' "$*" >&2; }

as_root() {
    if [ "$(id -u)" = 0 ]; then "$@"
    elif command -v sudo >/dev/null; then sudo "$@"
    else say "need root to run: $*"; exit 2; fi
}

cmd_deps() {
    local missing=() want=("${PACKAGES[@]}")
    [ "${1:-}" = --optional ] && want+=("${OPTIONAL[@]}")
    for p in "${want[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
    done
    if [ ${#missing[@]} -eq 0 ]; then
        return 0
    fi
    say "installing missing Debian packages: ${missing[*]}"
    as_root apt-get update -qq
    DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
}

cmd_build() {
    cmd_deps
    if [ ! -f "$BUILD/build.ninja" ]; then
        meson setup "$BUILD" --buildtype=release >&2
    fi
    ninja -C "$BUILD" >&2
}

build_san() {
    if [ ! -f "$SAN/build.ninja" ]; then
        meson setup "$SAN" --buildtype=debugoptimized -Db_sanitize=address,undefined \
            -Db_lundef=false >&2
    fi
    ninja -C "$SAN" >&2
}

cmd_test() {
    local slow=0
    [ "${1:-}" = "--slow" ] && slow=1
    cmd_build
    local rc=0
    local suites=(--suite unit --suite method --suite experiment)
    [ $slow = 1 ] && suites+=(--suite slow)
    say "release build: ${suites[*]}"
    meson test -C "$BUILD" "${suites[@]}" --print-errorlogs --num-processes 2 || rc=1
    say "sanitizer build (address, undefined): suite unit"
    build_san
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
        meson test -C "$SAN" --suite unit --print-errorlogs --num-processes 2 || rc=1
    return $rc
}

cmd_demo() {
    cmd_build
    mkdir -p results
    local scene=experiments/scenes/silo-demo.ini
    say "demo: $scene with the soft DEM backend -> results/demo.h5"
    "$BUILD/experiments/grano" run "$scene" --method dem --out results/demo.h5 --force \
        --snapshot results/demo.png
    "$BUILD/experiments/grano" info results/demo.h5
}

cmd_bench() {
    cmd_build
    # Peers are heavy and only the comparison needs them: install on demand.
    if [[ " $* " == *" --peer lammps "* || " $* " == *" --peer=lammps "* ]] && ! command -v lmp >/dev/null; then
        say "installing the LAMMPS peer (Debian package lammps)"
        as_root apt-get update -qq
        DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq lammps >&2
    fi
    "$BUILD/experiments/grano" bench "$@"
}

# Debian's python3 (numpy, h5py, pandas), not the first on PATH, with the
# module grano of the build (docs/python.md).
cmd_python() {
    cmd_build
    PYTHONPATH="$PWD/$BUILD/python${PYTHONPATH:+:$PYTHONPATH}" exec /usr/bin/python3 "$@"
}

usage() {
    cat <<USAGE
usage: ./grano.sh COMMAND
  deps [--optional]  install the Debian packages grano needs (only the missing ones);
                  --optional adds lammps (for --peer lammps) and ffmpeg (grano movie to MP4)
  build           deps, then configure and build into $BUILD/
  demo            build, then run the silo discharge demo (results/demo.h5, results/demo.png)
  test [--slow]   build, then the meson suites (unit, method, experiment; slow with --slow),
                  then the unit suite again under address and undefined-behaviour sanitizers
  bench ARGS      build, then grano bench ARGS (e.g. ./grano.sh bench dem); with
                  --peer lammps, Debian's lammps package is installed if missing
  run ARGS        build, then grano ARGS (e.g. ./grano.sh run methods,
                  ./grano.sh run info results/demo.h5)
  python ARGS     build, then /usr/bin/python3 ARGS with the module grano importable
                  (PYTHONPATH=$BUILD/python; e.g. ./grano.sh python examples/python/silo.py)
USAGE
}

case "${1:-}" in
    deps) shift; cmd_deps "$@" ;;
    build) cmd_build ;;
    demo) cmd_demo ;;
    test) shift; cmd_test "$@" ;;
    bench) shift; cmd_bench "$@" ;;
    run) shift; cmd_build; exec "$BUILD/experiments/grano" "$@" ;;
    python) shift; cmd_python "$@" ;;
    -h|--help|help) usage ;;
    *) usage >&2; exit 2 ;;
esac
