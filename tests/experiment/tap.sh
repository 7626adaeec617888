# Sourced by the TAP test scripts of this folder: a temporary folder $tmp
# removed at exit, and ok / notok / check that number the tests and count
# failures (notok shows $tmp/err when present). End a script with
# `finish` (or `echo "1..$n"; [ $fails = 0 ]`).
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0
fails=0
ok() { n=$((n + 1)); echo "ok $n - $1"; }
notok() { n=$((n + 1)); echo "not ok $n - $1"; fails=$((fails + 1)); [ -f "$tmp/err" ] && sed 's/^/# /' "$tmp/err"; }
check() { if [ "$1" = 0 ]; then ok "$2"; else notok "$2"; fi; }
finish() { echo "1..$n"; exit $((fails > 0)); }
# refusals SUB "ARGS:FLAG" ...: each `$GRANO SUB ARGS` (split on spaces)
# exits 2 naming FLAG on stderr.
refusals() {
    local sub=$1 args cmd flag rc
    shift
    for args in "$@"; do
        cmd=${args%%:*}
        flag=${args##*:}
        # shellcheck disable=SC2086
        "$GRANO" "$sub" $cmd >"$tmp/out" 2>"$tmp/err"
        rc=$?
        [ $rc = 2 ] && grep -q -- "$flag" "$tmp/err"
        check $? "$sub $cmd exits 2 naming $flag (got $rc)"
    done
}
