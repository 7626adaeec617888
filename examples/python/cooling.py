"""Homogeneous cooling on two methods: DSMC against event-driven MD.

2000 inelastic disks (restitution 0.9, packing fraction 0.05, periodic box)
start from one elastic warm-up state (3 collisions per disk, edmd) and cool;
edmd resolves every collision, DSMC (its Enskog mode, cells of 10 d, as
grano course cooling runs it) samples them. The temperature of the two
runs, T(t)/T0 at 8 times up to 0.9 tau (about 7 collisions per disk), must
agree within 5 %, and each follow Haff's law T0 / (1 + t/tau)^2 with Enskog's
tau within 6 % (the bound of grano course cooling).

    PYTHONPATH=build/python /usr/bin/python3 examples/python/cooling.py [--plot cooling.png]
"""
import math
import sys

import numpy as np

import grano

N, ETA, ALPHA = 2000, 0.05, 0.9
L = math.sqrt(N * math.pi / 4 / ETA)
TOLERANCE, HAFF_TOLERANCE = 0.05, 0.06


def scene(alpha, **extra):
    d = {"scene": {"name": "cooling", "seed": 1},
         "domain": {"width": L, "height": L, "left": "periodic", "right": "periodic",
                    "bottom": "periodic", "top": "periodic"},
         "material": {"restitution": alpha},
         "species": {"diameter": 1, "count": N},
         "init": {"kind": "lattice", "spacing": 0.99 * L / math.ceil(math.sqrt(N)),
                  "velocity": "gaussian", "v0": 1}}
    d.update(extra)
    return grano.Scene(d)


def chi(eta):
    """Luding's pair correlation at contact for hard disks."""
    u = 1 - eta
    return (1 - 7 * eta / 16) / (u * u) - eta ** 3 / (128 * u ** 4)


def cool(method, start, times, **extra):
    sim = grano.Sim(scene(ALPHA, **extra), method=method, init=start)
    T = []
    for t in times:
        sim.advance(t)
        T.append(sim.observables()["temperature"])
    return np.array(T), sim.counters()["pair_collisions"] / N


def main(argv):
    warm = grano.Sim(scene(1.0), method="edmd")
    while warm.counters()["pair_collisions"] < 3 * N:
        warm.advance(warm.time + 1)
    start = warm.snapshot()
    T0 = warm.observables()["temperature"]
    tau = 2 / ((1 - ALPHA ** 2) * (N / L ** 2) * chi(ETA) * math.sqrt(math.pi * T0))
    times = np.linspace(0, 0.9 * tau, 9)[1:]
    # the sample times count from the start of each run
    (edmd, per_disk), (dsmc, _) = cool("edmd", start, times), cool("dsmc", start, times,
                                                                 dsmc={"enskog": True, "cell": 10})
    edmd, dsmc = edmd / T0, dsmc / T0
    haff = 1 / (1 + times / tau) ** 2
    diff = np.max(np.abs(dsmc / edmd - 1))
    off_e, off_d = np.max(np.abs(edmd / haff - 1)), np.max(np.abs(dsmc / haff - 1))
    print("cooling: %d disks, alpha %g, eta %g, tau %.4g; %.2f collisions per disk (edmd)"
          % (N, ALPHA, ETA, tau, per_disk))
    print("    t       edmd T/T0  dsmc T/T0  Haff")
    for row in zip(times, edmd, dsmc, haff):
        print("  %6.2f  %9.5f  %9.5f  %9.5f" % row)
    print("largest difference dsmc/edmd %.2f %% (tolerance %g %%); from Haff's law: edmd %.2f %%, dsmc %.2f %%"
          % (100 * diff, 100 * TOLERANCE, 100 * off_e, 100 * off_d))
    if "--plot" in argv:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        plt.loglog(1 + times / tau, edmd, "o", label="edmd")
        plt.loglog(1 + times / tau, dsmc, "s", label="dsmc (Enskog)")
        plt.loglog(1 + times / tau, haff, "k--", label="Haff")
        plt.xlabel("1 + t / tau")
        plt.ylabel("T / T0")
        plt.legend()
        plt.savefig(argv[argv.index("--plot") + 1])
    assert diff < TOLERANCE, "dsmc and edmd differ by %.3g" % diff
    assert max(off_e, off_d) < HAFF_TOLERANCE, "Haff's law missed by %.3g, %.3g" % (off_e, off_d)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
