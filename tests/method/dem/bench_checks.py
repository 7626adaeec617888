#!/usr/bin/env python3
"""The dem benchmark program's two modes, checked on what they print:
throughput (a RESULT line with the sizes asked for and a finite positive
rate; with --scaling, a speed-up and the two threads' cache-line round
trip, which no machine makes shorter than a few nanoseconds: a probe
whose threads did not take turns would print less) and the
speed-against-error sweep (each integrator's error against
the CVODE reference falls at its order as dt halves: Verlet and Gear 2 on
the collision, explicit Euler 1; on the slow packing Verlet and Gear sit at
the reference's own tolerance and Euler halves exactly).

usage: bench_checks.py GRANO OUTDIR
"""
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from bench_tap import check, run  # noqa: E402


def throughput(grano):
    out = run([grano, "bench", "dem", "--n", "400", "--steps", "50", "--settle", "10"])
    m = re.search(r"^RESULT method=dem n=(\d+) steps=(\d+) particle_steps_per_s=(\S+)$", out, re.M)
    bad = check(m is not None, "bench dem prints its RESULT line")
    if m:
        rate = float(m.group(3))
        bad += check(m.group(1) == "400" and m.group(2) == "50", "RESULT names n = 400, steps = 50")
        bad += check(math.isfinite(rate) and rate > 0, "rate %.3g particle-steps/s is finite and positive" % rate)
    return bad


def scaling(grano):
    out = run([grano, "bench", "dem", "--n", "400", "--steps", "200", "--settle", "10", "--scaling"])
    m = re.search(r"^RESULT method=dem n=400 steps=200 \S+ threads=2 speedup=(\S+) c2c_ns=(\S+),(\S+)$", out, re.M)
    bad = check(m is not None, "bench dem --scaling prints its RESULT line with c2c_ns")
    if m:
        sp, a, b = (float(m.group(k)) for k in (1, 2, 3))
        bad += check(math.isfinite(sp) and sp > 0, "speed-up %.3g is finite and positive" % sp)
        bad += check(all(5 < v < 1e7 for v in (a, b)), "round trips %.0f and %.0f ns within (5 ns, 10 ms)" % (a, b))
    return bad


def sweep(grano, outdir):
    run([grano, "bench", "dem", "--accuracy", "--quick", "--dir", outdir])
    rows = {}
    with open(os.path.join(outdir, "dem_accuracy.dat")) as f:
        for line in f:
            w = line.split()
            if len(w) == 8 and not line.startswith("#"):
                rows.setdefault((w[0], w[1]), []).append([float(x) for x in w[2:]])
    bad = check(os.path.getsize(os.path.join(outdir, "dem_accuracy.png")) > 1000, "the sweep's figure is written")

    def ratios(key, col):
        r = sorted(rows.get(key, []), key=lambda v: -v[0])
        return [round(a[col] / b[col], 3) for a, b in zip(r, r[1:]) if abs(b[0] / a[0] - 0.5) < 1e-4]

    # collision: restitution error (column 3) as dt halves
    for integ, lo, hi in (("verlet", 3.0, 5.5), ("euler", 1.6, 2.8)):
        q = ratios(("collision", integ), 3)
        bad += check(len(q) >= 2 and all(lo <= x <= hi for x in q),
                     "collision %s: error ratios %s per halving in [%g, %g]" % (integ, q, lo, hi))
    g = sorted(rows.get(("collision", "gear"), []), key=lambda v: v[0])
    bad += check(len(g) >= 1 and g[0][3] < 5e-3, "collision gear at the finest dt: restitution error < 5e-3")
    for integ in ("verlet", "gear"):
        e = [v[5] for v in rows.get(("packing", integ), [])]
        bad += check(len(e) == 3 and max(e) < 1e-9, "packing %s: position errors %s below 1e-9 d" % (integ, e))
    q = ratios(("packing", "euler"), 5)
    bad += check(len(q) == 2 and all(abs(x - 2) < 0.05 for x in q), "packing euler: first order, ratios %s" % q)
    return bad


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    os.makedirs(argv[2], exist_ok=True)
    bad = throughput(argv[1]) + scaling(argv[1]) + sweep(argv[1], argv[2])
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
