"""A silo discharge with a live plot.

400 frictional disks settle in a silo 20 d wide; its 6 d orifice opens at
t = 1 and grains leave through it. Every 0.5 tau the figure is redrawn: the
grains coloured by speed, and the outflow against time. In Jupyter the
figure updates in place (IPython.display); elsewhere (here, the Agg
backend) it is drawn each time and written once at the end. Checked: no
grain leaves before the orifice opens, grains keep leaving after (the
outflow grows in every second after the first), and every grain is either
still inside or counted in the outflow.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/silo.py [silo.png]
"""
import sys

import numpy as np

import grano

SCENE = {
    "scene": {"name": "silo-python", "seed": 3},
    "domain": {"width": 22, "height": 45, "bottom": "open", "gravity": 1},
    "material": {"normal": "linear", "tangential": "coulomb", "kn": 1e4, "mu": 0.5, "restitution": 0.5},
    "species": {"diameter": 1, "count": 400},
    "silo": {"width": 20, "height": 40, "base": 5, "orifice": 6, "open_time": 1},
    "init": {"kind": "lattice", "spacing": 1.05, "velocity": "gaussian", "v0": 0.5},
}
UNTIL, EVERY = 10.0, 0.5


def in_notebook():
    try:
        from IPython import get_ipython
        return get_ipython() is not None and "IPKernelApp" in get_ipython().config
    except ImportError:
        return False


def live_run(sim, until, every):
    """Advance sim to until, redrawing the figure every `every`."""
    import matplotlib
    if not in_notebook():
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import EllipseCollection

    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(9, 6), gridspec_kw={"width_ratios": [1, 1.2]},
                                  constrained_layout=True)
    snap = sim.snapshot()
    silo = SCENE["silo"]
    left, right = 1, 1 + silo["width"]
    gap = ((left + right - silo["orifice"]) / 2, (left + right + silo["orifice"]) / 2)
    ax.plot([left, left, gap[0]], [silo["base"] + silo["height"], silo["base"], silo["base"]], "k-")
    ax.plot([gap[1], right, right], [silo["base"], silo["base"], silo["base"] + silo["height"]], "k-")
    ax.set(xlim=(0, 22), ylim=(-5, 45), aspect="equal", xlabel="x / d", ylabel="y / d")
    disks = EllipseCollection(2 * snap.radius, 2 * snap.radius, np.zeros(len(snap)), units="xy",
                              offsets=snap.positions, offset_transform=ax.transData, cmap="viridis")
    disks.set_clim(0, 3)
    ax.add_collection(disks)
    fig.colorbar(disks, ax=ax, label="speed / (d / tau)")
    line, = ax2.plot([], [], "o-")
    ax2.set(xlim=(0, until), xlabel="t / tau", ylabel="grains out", title="outflow")
    times, out = [], []
    handle = None
    while sim.time < until - 1e-9:
        sim.advance(min(until, sim.time + every))
        snap, obs = sim.snapshot(), sim.observables()
        # grains that left stay in the snapshot, flagged gone: not drawn
        disks.set_offsets(np.where(snap.mobile[:, None], snap.positions, np.nan))
        disks.set_array(np.hypot(snap.vx, snap.vy))
        times.append(sim.time)
        out.append(obs["outflow"])
        line.set_data(times, out)
        ax2.set_ylim(0, max(out) + 5)
        ax.set_title("t = %.1f" % sim.time)
        if in_notebook():
            from IPython import display
            handle = handle or display.display(fig, display_id=True)
            handle.update(fig)
        else:
            fig.canvas.draw()
    return fig, np.array(times), np.array(out)


def main(argv):
    sim = grano.Sim(grano.Scene(SCENE), method="dem")
    fig, times, out = live_run(sim, UNTIL, EVERY)
    png = argv[1] if len(argv) > 1 else "silo.png"
    fig.savefig(png)
    n_in = sim.observables()["n_mobile"]
    print("silo: %d grains out by t = %g (%.1f per tau after the opening), %d inside; figure %s"
          % (out[-1], UNTIL, (out[-1] - out[times <= 2][-1]) / (UNTIL - 2), n_in, png))
    assert np.all(out[times <= 1] == 0), "grains left before the orifice opened"
    per_second = out[times == np.round(times)]
    assert np.all(np.diff(per_second[1:]) > 0), "the discharge stopped: %s" % per_second
    assert n_in + out[-1] == SCENE["species"]["count"], "grains lost: %d in, %d out" % (n_in, out[-1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
