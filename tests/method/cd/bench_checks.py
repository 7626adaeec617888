#!/usr/bin/env python3
"""grano bench cd --quick, checked on what it prints: a RESULT line per case
(pile, silo) with finite positive contact updates and steps per second and
sweeps per step, the pile's WARM line with a finite positive factor, and,
when grano was built with Siconos, a finite positive siconos_ratio on the
cases it compares. No timing is asserted beyond that.

usage: bench_checks.py GRANO SICONOS(0|1)
"""
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from bench_tap import check, run  # noqa: E402

LINE = re.compile(r"^RESULT method=cd case=(\w+) n=(\d+) contact_updates_per_s=(\S+) steps_per_s=(\S+)"
                  r" iterations_per_step=(\S+)(?: siconos_ratio=(\S+))?$", re.M)


def positive(s):
    try:
        x = float(s)
    except (TypeError, ValueError):
        return False
    return math.isfinite(x) and x > 0


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    r = subprocess.run([argv[1], "bench", "cd", "--quick"], capture_output=True, text=True)
    if r.returncode:
        sys.exit("grano bench cd --quick: exit %d\n%s%s" % (r.returncode, r.stdout, r.stderr))
    siconos = argv[2] == "1"
    lines = {m.group(1): m for m in LINE.finditer(r.stdout)}
    bad = check(sorted(lines) == ["pile", "silo"], "RESULT lines for pile and silo (got %s)" % sorted(lines))
    for case, m in sorted(lines.items()):
        rates = m.group(3, 4, 5)
        bad += check(all(positive(x) for x in rates),
                     "%s: updates/s, steps/s, sweeps/step %s finite and positive" % (case, list(rates)))
        if siconos:
            bad += check(positive(m.group(6)), "%s: siconos_ratio %s finite and positive" % (case, m.group(6)))
        else:
            bad += check(m.group(6) is None, "%s: no siconos_ratio without Siconos" % case)
    w = re.search(r"^WARM method=cd case=pile n=\d+ warm_iterations_per_step=(\S+) "
                  r"cold_iterations_per_step=(\S+) factor=(\S+)$", r.stdout, re.M)
    bad += check(w is not None and all(positive(x) for x in w.groups()),
                 "the pile's WARM line with a finite positive factor")
    print(r.stdout, end="")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
