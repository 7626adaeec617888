"""What the benches' checking scripts (tests/method/*/bench_checks.py)
share: a command's standard output, or the script's exit with the command's
output when it fails; a TAP line per check."""
import subprocess
import sys


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode:
        sys.exit("%s: exit %d\n%s%s" % (" ".join(cmd), r.returncode, r.stdout, r.stderr))
    return r.stdout


def check(cond, what):
    print(("ok - " if cond else "not ok - ") + what)
    return 0 if cond else 1
