#!/usr/bin/env python3
"""grano bench dsmc, checked on what it prints (not on speed): the RESULT
line per N with a finite positive rate, collisions per particle and step
equal to nu dt = 0.2 (the bench's dt is 0.2 mean free times) within 3 %,
and the state's bytes per particle within 72 (positions, velocities and the
sort's buffer, 8 bytes each; rank, cell, order and the last two partners, 4
each; the id, 8; the cells' starts); the comparison with edmd (a RATIO line
whose final temperatures agree within 5 %); the threads (a SCALING line
whose two states are the same bits); the generator timings (one RESULT line
per generator).

usage: bench_checks.py GRANO
"""
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from bench_tap import check, run  # noqa: E402


def throughput(grano):
    out = run([grano, "bench", "dsmc", "--n", "1000,20000"])
    pat = (r"^RESULT method=dsmc n=(\d+) particle_moves_per_s=(\S+) collisions_per_particle_step=(\S+) "
           r"bytes_per_particle=(\S+)$")
    rows = re.findall(pat, out, re.M)
    bad = check([r[0] for r in rows] == ["1000", "20000"], "one RESULT line per N asked (%d)" % len(rows))
    for n, rate, coll, mem in rows:
        rate, coll, mem = float(rate), float(coll), float(mem)
        bad += check(math.isfinite(rate) and rate > 0, "N = %s: %.3g moves/s finite and positive" % (n, rate))
        bad += check(abs(coll / 0.2 - 1) < 0.03, "N = %s: %.4f collisions per particle-step = 0.2 within 3 %%" % (n, coll))
        bad += check(0 < mem <= 72, "N = %s: %.1f bytes per particle <= 72" % (n, mem))
    return bad


def compare(grano):
    out = run([grano, "bench", "dsmc", "--compare", "--quick"])
    m = re.search(r"^RATIO method=dsmc peer=edmd n=2000 rounds=1 cpu_ratio=(\S+) t_ratio=(\S+)$", out, re.M)
    bad = check(m is not None, "bench dsmc --compare prints its RATIO line")
    if m:
        cpu, tr = float(m.group(1)), float(m.group(2))
        bad += check(math.isfinite(cpu) and cpu > 0, "cpu ratio %.3g finite and positive" % cpu)
        bad += check(abs(tr - 1) < 0.05, "dsmc's T(t_end) over edmd's %.4f within 5 %% of 1" % tr)
    return bad


def threads(grano):
    out = run([grano, "bench", "dsmc", "--threads", "1,2", "--n", "20000", "--rounds", "1"])
    m = re.search(r"^SCALING method=dsmc n=20000 threads=1,2 speedup=(\S+) ceiling=\S+ of_ceiling=\S+ identical=(\d)$", out, re.M)
    bad = check(m is not None, "bench dsmc --threads prints its SCALING line")
    if m:
        bad += check(m.group(2) == "1", "one and two threads give the same bits")
        bad += check(float(m.group(1)) > 0, "speedup %s positive" % m.group(1))
    return bad


def rng(grano):
    out = run([grano, "bench", "dsmc", "--rng"])
    rows = re.findall(r"^RESULT rng=(\S+) draws_per_s=(\S+)$", out, re.M)
    names = [r[0] for r in rows]
    bad = check("gsl_mt19937" in names and "philox2x64_10" in names, "--rng times mt19937 and philox2x64 (%s)" % names)
    return bad + check(all(float(r[1]) > 0 for r in rows), "every draw rate positive")


def main(argv):
    if len(argv) != 2:
        sys.exit(__doc__)
    bad = throughput(argv[1]) + compare(argv[1]) + threads(argv[1]) + rng(argv[1])
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
