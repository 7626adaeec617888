# TAP helpers for the experiment tests (sourced): a scratch directory $tmp
# removed on exit, ok/notok (notok shows $tmp/err), finish prints the plan
# and exits 1 if anything failed.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0
fails=0
ok() { n=$((n + 1)); echo "ok $n - $1"; }
notok() {
    n=$((n + 1))
    echo "not ok $n - $1"
    fails=$((fails + 1))
    [ -f "$tmp/err" ] && sed 's/^/# /' "$tmp/err"
}
finish() { echo "1..$n"; exit $((fails > 0)); }
