# TAP helpers sourced by the experiment scripts: a temporary directory
# $tmp removed on exit, ok/notok/check counting into $n and $fails (notok
# prints $tmp/err as comments), done_tap printing the plan and exiting.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
n=0
fails=0
ok() { n=$((n + 1)); echo "ok $n - $1"; }
notok() { n=$((n + 1)); echo "not ok $n - $1"; fails=$((fails + 1)); [ -f "$tmp/err" ] && sed 's/^/# /' "$tmp/err"; }
check() { if [ "$1" = 0 ]; then ok "$2"; else notok "$2"; fi; }
done_tap() { echo "1..$n"; exit $((fails > 0)); }
