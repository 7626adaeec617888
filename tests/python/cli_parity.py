#!/usr/bin/env python3
"""A run from Python is grano run's run, bit for bit, on every method.

For each method, one shipped scene run by `grano run --until T` and by
grano.Sim(...).advance over the same frame times: every frame's positions,
velocities, spins and flags, every observables sample (Sim.history()), the
coarse-grained fields of every frame (observe_every = output_every, so a
frame's field is one sample) and the checkpoint at T (Sim.save against the
CLI's <out>.ckpt: every dataset and attribute) are the same bits. Then each
continues the other's checkpoint to 2T (grano run --restart from Sim.save's
file; Sim.load of the CLI's) and the final frames agree exactly. First, the
issue's one-liner prints the temperature the CLI writes.

usage: cli_parity.py GRANO SOURCE_ROOT WORKDIR (TAP)
"""
import os
import subprocess
import sys

import numpy as np

from common import Tap, cli, h5_diffs, setup

# method: scene, end time; lgca has no particles, so its fields and
# observables are compared
CASES = {
    "edmd": ("box", 1.0),
    "dem": ("box", 0.2),
    "cd": ("box", 0.2),
    "dsmc": ("vibrated", 0.4),
    "lgca": ("lgca-pipe", 40),
}
SETS = {"box": "3 3", "vibrated": "4 2", "lgca-pipe": "3 61"}


def frame_times(f):
    """The frames' times: the trajectory's, or (lattice) the fields'."""
    if "particles/trajectory/position" in f:
        return f["particles/trajectory/position/time"][()]
    return f["fields/packing_fraction/time"][()]


def same_last(f, hist):
    """The file's last observables sample against the history's last row."""
    row = hist.iloc[-1]
    for name in f["observables"]:
        v = f["observables/%s/value" % name][-1]
        mine = np.array([row[name + "_x"], row[name + "_y"]]) if np.ndim(v) else row[name]
        if not np.array_equal(v, mine, equal_nan=True):
            return False
    return True


def compare_run(tap, grano, exe, root, method, scene, until):
    import h5py
    ini = "%s/experiments/scenes/%s.ini" % (root, scene)
    # a frame's fields average the samples since the last frame: one here
    sets = ["run.output_every=%r" % (until / 4), "run.observe_every=%r" % (until / 4),
            "measure.field_cells=" + SETS[scene]]
    out = "cli-%s.h5" % method
    rc, err = cli(exe, "run", ini, "-m", method, "--until", until, "-o", out, "-f", "-q",
                  *sum((["--set", s] for s in sets), []))
    if rc:
        tap.check(False, "%s: grano run" % method, err)
        return
    sc = grano.Scene(ini)
    for s in sets:
        sc.set(*s.split("=", 1))
    sim = grano.Sim(sc, method)
    bad = []
    with h5py.File(out, "r") as f:
        tr = f.get("particles/trajectory")
        particles = "particles/trajectory/position" in f
        times = frame_times(f)
        for i, t in enumerate(times):
            sim.advance(t)
            if particles:
                snap = sim.snapshot()
                for name, mine in (("position", snap.positions), ("velocity", snap.velocities),
                                   ("omega", snap.omega), ("flags", snap.flags)):
                    if not np.array_equal(tr[name + "/value"][i], mine):
                        bad.append("frame %d %s" % (i, name))
            fl = sim.fields()
            for name, key in (("packing_fraction", "packing_fraction"), ("velocity", "velocity"),
                              ("temperature", "temperature")):
                g = f["fields/" + name]
                k = int(np.searchsorted(g["time"][()], sim.time))
                if k >= len(g["time"]) or not np.array_equal(g["value"][k], fl[key], equal_nan=True):
                    bad.append("frame %d field %s" % (i, name))
        sim.advance(until)
        h = sim.history()
        for name in f["observables"]:
            v = f["observables/%s/value" % name][()]
            mine = np.column_stack((h[name + "_x"], h[name + "_y"])) if v.ndim == 2 else h[name].to_numpy()
            if v.shape != mine.shape or not np.array_equal(v, mine, equal_nan=True):
                bad.append("observable %s" % name)
        if not np.array_equal(f["observables/%s/step" % name][()], h["step"].to_numpy()):
            bad.append("observable steps")
    tap.check(not bad, "%s on %s to t = %g: %d frames, %d observable samples and the fields the same bits as "
              "grano run's" % (method, scene, until, len(times), len(h)), "; ".join(bad[:10]))
    sim.save("py-%s.ckpt" % method)
    d = h5_diffs("py-%s.ckpt" % method, "cli-%s.ckpt" % method)
    tap.check(not d, "%s: Sim.save's checkpoint holds the same bits as grano run's" % method, d[:10])
    # each continues the other's checkpoint (into a new file: an existing
    # --out is continued, and one left by an earlier build may not fit)
    if os.path.exists("cont-%s.h5" % method):
        os.remove("cont-%s.h5" % method)
    rc, err = cli(exe, "run", ini, "-m", method, "--until", 2 * until, "-o", "cont-%s.h5" % method, "-f", "-q",
                  "--restart", "py-%s.ckpt" % method, *sum((["--set", s] for s in sets), []))
    loaded = grano.Sim.load("cli-%s.ckpt" % method)
    loaded.advance(2 * until)
    sim.advance(2 * until)
    with h5py.File("cont-%s.h5" % method, "r") as f:
        same = rc == 0 and same_last(f, loaded.history()) and same_last(f, sim.history())
        if particles:
            last = f["particles/trajectory/position/value"][-1]
            same = same and np.array_equal(last, loaded.snapshot().positions) and \
                np.array_equal(last, sim.snapshot().positions)
    tap.check(same, "%s: grano run --restart of Sim.save's checkpoint, Sim.load of grano run's and the "
              "uninterrupted Sim agree at t = %g" % (method, 2 * until), err)


def main(argv):
    exe, root, work = setup(argv)
    import grano
    import h5py
    tap = Tap()
    ini = "%s/experiments/scenes/box.ini" % root
    rc, err = cli(exe, "run", ini, "--method", "edmd", "--until", 1, "-o", "box-edmd.h5", "-f", "-q")
    with h5py.File("box-edmd.h5", "r") as f:
        want = f["observables/temperature/value"][-1]
    code = ("import grano; s = grano.Sim(grano.Scene('%s'), method='edmd'); s.advance(1.0); "
            "print(s.observables()['temperature'])" % ini)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    got = r.stdout.strip()
    tap.check(rc == 0 and r.returncode == 0 and float(got) == want,
              "the one-liner prints %s, the temperature grano run writes (%r)" % (got, want), err + r.stderr)
    # the scene's own intervals: observables every 0.05, frames every 0.5
    sim = grano.Sim(grano.Scene(ini), "edmd").advance(1.0)
    h = sim.history()
    with h5py.File("box-edmd.h5", "r") as f:
        bad = [n for n in f["observables"] if not np.array_equal(
            f["observables/%s/value" % n][()], np.column_stack((h[n + "_x"], h[n + "_y"]))
            if n + "_x" in h else h[n].to_numpy(), equal_nan=True)]
    tap.check(not bad and len(h) == 21, "edmd on box, the scene's intervals: %d observable samples (window "
              "averages included) the same bits as grano run's" % len(h), bad)
    for method, (scene, until) in CASES.items():
        compare_run(tap, grano, exe, root, method, scene, until)
    return tap.finish()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
