"""The Maxwell exercise (docs/course.md, section 1) from Python.

Elastic disks started on a lattice, all at speed V0 in random directions,
relax to Maxwell's speed law F(v) = 1 - exp(-v^2/V0^2) (2-D, <v^2> = V0^2)
within a few collisions per disk. The Kolmogorov-Smirnov distance of the
speeds to that law, after 10 collisions per disk and pooled over 4 starts,
must lie below 1.63/sqrt(n), the 1 % critical value for n samples of the
law itself; at the start it is 1 - 1/e.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/maxwell.py [--plot maxwell.png]
"""
import math
import sys

import numpy as np

import grano

N, RUNS, V0 = 400, 4, 1.0
L = math.sqrt(N * math.pi / 4 / (math.pi / 16))   # packing fraction pi/16, as the course
COLLISIONS = 10


def scene(seed):
    return grano.Scene({
        "scene": {"name": "maxwell", "seed": seed},
        "domain": {"width": L, "height": L},
        "material": {"restitution": 1},
        "species": {"diameter": 1, "count": N},
        "init": {"kind": "lattice", "spacing": 0.99 * L / math.ceil(math.sqrt(N)),
                 "velocity": "speed", "v0": V0},
    })


def ks_distance(v):
    """sup |F_n - F| of the samples v against Maxwell's law."""
    v = np.sort(v)
    F = 1 - np.exp(-v * v / V0 ** 2)
    n = len(v)
    return max(np.max(np.arange(1, n + 1) / n - F), np.max(F - np.arange(n) / n))


def speeds_after(seed, collisions):
    sim = grano.Sim(scene(seed), method="edmd")
    start = np.hypot(*sim.snapshot().velocities.T)
    t = 0.0
    while sim.counters()["pair_collisions"] < collisions * N:
        t += 0.5
        sim.advance(t)
    snap = sim.snapshot()
    return start, np.hypot(snap.vx, snap.vy)


def main(argv):
    start, end = zip(*(speeds_after(seed, COLLISIONS) for seed in range(1, RUNS + 1)))
    start, end = np.concatenate(start), np.concatenate(end)
    d0, d = ks_distance(start), ks_distance(end)
    bound = 1.63 / math.sqrt(len(end))
    print("maxwell: %d elastic disks x %d starts; KS distance to Maxwell %.4f at the start, "
          "%.4f after %d collisions per disk (1 %% critical value %.4f)" % (N, RUNS, d0, d, COLLISIONS, bound))
    if "--plot" in argv:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        v = np.linspace(0, 3, 200)
        plt.hist(end, bins=30, density=True, histtype="step", label="after %d collisions per disk" % COLLISIONS)
        plt.plot(v, 2 * v / V0 ** 2 * np.exp(-v * v / V0 ** 2), "k--", label="Maxwell")
        plt.xlabel("speed v / V0")
        plt.ylabel("f(v)")
        plt.legend()
        plt.savefig(argv[argv.index("--plot") + 1])
    assert abs(d0 - (1 - math.exp(-1))) < 1e-9, "the start is not at one speed: KS %g" % d0
    assert d < bound, "speeds not Maxwellian: KS %.4f above %.4f" % (d, bound)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
