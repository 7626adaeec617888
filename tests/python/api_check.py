#!/usr/bin/env python3
"""The Python module's objects (docs/python.md), each against the grano
program where it has a counterpart: scene refusals carry grano run's
messages; the registry is grano methods'; snapshots are views; a failed
run raises its diagnostic and keeps the last good state; validity limits
warn; Ctrl-C stops an advance between two calls into C, leaving a state
that runs on; the GIL is free while a method runs; grano.read gives a
result's tables and arrays as h5py reads them.

usage: api_check.py GRANO SOURCE_ROOT WORKDIR (TAP)
"""
import contextlib
import io
import signal
import subprocess
import sys
import threading
import time
import warnings

import numpy as np

from common import Tap, cli, setup


def refusals(tap, grano, exe, root):
    ini = "%s/experiments/scenes/box.ini" % root
    for key, value in (("material.muu", "0.3"), ("material.mu", "-1"), ("dem.dt", "0.01")):
        rc, err = cli(exe, "run", ini, "-m", "dem", "--set", "%s=%s" % (key, value), "-o", "x.h5", "-f", "-q")
        try:
            grano.Sim(grano.Scene(ini).set(key, value), "dem")
            msg = None
        except grano.SceneError as e:
            msg = str(e)
        tap.check(rc == 2 and msg is not None and err.strip() == "grano run: " + msg and key in msg,
                  "--set %s=%s: grano.SceneError with grano run's message (%s)" % (key, value, msg), err)
    with open("bad.ini", "w") as f:
        f.write("[domain]\nwidth = 10\nheight = ten\n[species]\ncount = 3\n")
    rc, err = cli(exe, "run", "bad.ini", "-o", "x.h5", "-f", "-q")
    try:
        grano.Scene("bad.ini")
        msg = None
    except grano.SceneError as e:
        msg = str(e)
    tap.check(msg is not None and msg.startswith("bad.ini:3:") and err.strip() == "grano run: " + msg,
              "a bad line: grano.SceneError naming file:line as grano run does (%s)" % msg, err)
    try:
        grano.Scene({"domain": {"width": 10, "height": 10, "widht": 3}, "species": {"count": 3}})
        msg = None
    except grano.SceneError as e:
        msg = str(e)
    tap.check(msg is not None and "'widht'" in msg and "'width'" in msg,
              "a dict scene's bad key: grano.SceneError naming it (%s)" % msg)
    try:
        grano.Sim(ini, "lgca")
        msg = None
    except grano.SceneError as e:
        msg = str(e)
    tap.check(msg is not None and msg.startswith(ini + ":") and "friction" in msg,
              "a feature the method lacks: refused naming the scene's line (%s)" % msg)
    with contextlib.suppress(ValueError):
        grano.Sim(ini, "dme")
        tap.check(False, "an unknown method is refused")
    try:
        grano.Sim(ini, "dme")
    except ValueError as e:
        tap.check("'dem'" in str(e), "an unknown method: ValueError naming the nearest (%s)" % e)


def registry(tap, grano, exe):
    out = subprocess.run([exe, "methods"], capture_output=True, text=True).stdout
    ms = grano.methods()
    names = [l.split(":")[0] for l in out.splitlines() if l and not l.startswith(" ")]
    tap.check(list(ms) == names, "grano.methods() lists grano methods' registry: %s" % ", ".join(ms))
    bad = []
    for m in ms.values():
        one = subprocess.run([exe, "methods", m.name], capture_output=True, text=True).stdout
        feats = [l for l in one.splitlines() if l.startswith("  features:")][0]
        keys = [l.split()[0] for l in one.split("parameters:")[1].splitlines()[2:] if l.strip()]
        obs = [l.split()[0] for l in one.split("observables (")[1].split("parameters:")[0].splitlines()[1:-1]]
        if [p.name for p in m.params] != keys or any(f not in feats for f in m.features) or \
                [o.name for o in m.observables] != obs or len(m.parameter_table()) != len(keys):
            bad.append(m.name)
    tap.check(not bad, "each method's features, observables and parameter table are grano methods NAME's", bad)


def snapshots(tap, grano, root):
    sim = grano.Sim("%s/experiments/scenes/box.ini" % root, "edmd").advance(0.5)
    s = sim.snapshot()
    views = all(not getattr(s, n).flags.owndata and getattr(s, n).base is not None for n in s._NAMES)
    again = np.shares_memory(s.x, s.x) and s.x.ctypes.data == s.x.ctypes.data
    tap.check(views and again and s.positions.flags.owndata and np.array_equal(s.positions[:, 0], s.x)
              and np.all(np.diff(s.id) > 0) and s.flags.dtype == np.uint32,
              "snapshot: x, y, vx, ... are views of its C arrays; positions a copy (structure of arrays); id order")
    x = s.x
    del s
    sim.advance(1.0)
    tap.check(np.all(np.isfinite(x)) and len(x) == 400, "a view outlives its snapshot object (it holds the memory)")
    start = sim.snapshot()
    twin = grano.Sim("%s/experiments/scenes/box.ini" % root, "edmd", init=start)
    tap.check(np.array_equal(twin.snapshot().positions, start.positions) and twin.time == 0.0,
              "Sim(..., init=snapshot) starts from that snapshot's grains")
    f = sim.fields((5, 4))
    c = sim.counters()
    tap.check(f["packing_fraction"].shape == (4, 5) and f["velocity"].shape == (4, 5, 2)
              and 0 < f["packing_fraction"].max() < 1 and c["events"] == sim.observables()["events"],
              "fields [ny][nx] and counters (%s)" % ", ".join("%s %d" % kv for kv in c.items()))
    t0, n0 = sim.time, sim.observables()["events"]
    sim.step(10)
    tap.check(sim.observables()["events"] == n0 + 10 and sim.time >= t0, "step(10): ten events")
    lat = grano.Sim("%s/experiments/scenes/lgca-pipe.ini" % root, "lgca")
    try:
        lat.snapshot()
        msg = None
    except grano.SceneError as e:
        msg = str(e)
    tap.check(msg is not None and "lgca" in msg, "a lattice has no snapshot, and says so (%s)" % msg)


def failures(tap, grano, exe, root):
    ini = "%s/experiments/scenes/box.ini" % root
    rc, err = cli(exe, "run", ini, "-m", "dem", "--set", "dem.max_overlap=0.001", "--until", 1, "-o", "u.h5",
                  "-f", "-q")
    sim = grano.Sim(grano.Scene(ini).set("dem.max_overlap", 0.001), "dem")
    try:
        sim.advance(1)
        msg = None
    except grano.RunError as e:
        msg = str(e)
    ok = msg is not None and rc == 1 and msg in err and "overlaps" in msg
    sim.save("last-good.ckpt")
    tap.check(ok and 0 < sim.time < 0.01 and sim.observables()["max_overlap"] > 0.001,
              "an unstable run: grano.RunError with grano run's diagnostic, the last good state kept "
              "(t = %g) and saved (%s)" % (sim.time, msg), err)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        grano.Sim("%s/experiments/scenes/vibrated.ini" % root, "dsmc").advance(0.3)
    got = [str(x.message) for x in w if x.category is grano.ValidityWarning]
    tap.check(len(got) == 1 and "limit_cell" in got[0] and "dsmc" in got[0],
              "a broken validity limit: one grano.ValidityWarning (%s)" % (got[0][:60] if got else got))


CHILD = """
import signal, sys, time
signal.signal(signal.SIGINT, signal.default_int_handler)
import grano
sim = grano.Sim(grano.Scene(sys.argv[1]), "dem")
print("ready", flush=True)
try:
    sim.advance(1e4)
except KeyboardInterrupt:
    t = sim.time
    sim.advance(t + 0.01)
    print("interrupted", t, sim.time, sim.observables()["n_mobile"], flush=True)
"""


def interrupt(tap, grano, root):
    p = subprocess.Popen([sys.executable, "-c", CHILD, "%s/experiments/scenes/box.ini" % root],
                         stdout=subprocess.PIPE, text=True)
    p.stdout.readline()
    time.sleep(1.0)
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
    try:
        out, _ = p.communicate(timeout=30)
    except subprocess.TimeoutExpired:
        p.kill()
        out = "(still running 30 s after SIGINT)"
    took = time.monotonic() - sent
    parts = out.split()
    ok = p.returncode == 0 and parts[:1] == ["interrupted"] and float(parts[2]) > float(parts[1]) > 0 \
        and parts[3] == "400"
    tap.check(ok and took < 5, "Ctrl-C: KeyboardInterrupt %.2f s after SIGINT, at t = %s, and the state "
              "runs on (%s)" % (took, parts[1] if ok else "?", out.strip()))


def gil(tap, grano, root):
    """One long call into C in a thread, through the handle that releases
    the GIL and through the one that holds it: Python in the main thread
    runs on in the first case only."""
    from grano import _lib
    import ctypes as C
    # no sample time before the end: one call runs the whole way
    sc = grano.Scene("%s/experiments/scenes/box.ini" % root).set("run.output_every", 5).set("run.observe_every", 5)\
        .set("run.checkpoint_every", 5)

    def count(handle, until):
        """Main-thread loops while the call runs, and the call's length."""
        sim = grano.Sim(sc, "dem")
        done, err, took, started = C.c_int(0), _lib.Err(), [], threading.Event()

        def one_call():
            started.set()
            t = time.perf_counter()
            handle.gp_sim_advance(sim._h, until, 0, C.byref(done), C.byref(err))
            took.append(time.perf_counter() - t)
        th = threading.Thread(target=one_call)
        n = 0
        th.start()
        started.wait()
        while th.is_alive():
            n += 1
        th.join()
        return n, took[0]
    # the held call's loops are those before it takes the GIL, a fixed
    # number, and the free call's grow with its length: a call of half a
    # second keeps the ratio clear of a loaded machine's (0.1 s gave 4.7)
    free, took = count(_lib.run, 10.0)
    held, took_held = count(_lib.lib, 10.0)
    tap.check(free > 5 * held, "the GIL is released in advance: during a %.2f s call the main thread looped "
              "%d times (%d during a %.2f s call that holds it)" % (took, free, held, took_held))
    buf = io.StringIO()
    with contextlib.redirect_stderr(buf):
        grano.Sim("%s/experiments/scenes/box.ini" % root, "edmd").advance(0.5, progress=True)
    tap.check("0.5" in buf.getvalue() or "it/s" in buf.getvalue() or "tau" in buf.getvalue(),
              "advance(progress=True) shows progress (%s)" % buf.getvalue().strip()[-60:])


def reading(tap, grano, exe, root):
    import h5py
    ini = "%s/experiments/scenes/box.ini" % root
    cli(exe, "run", ini, "-m", "dem", "--until", 0.2, "--set", "measure.field_cells=3 3", "-o", "r.h5", "-f", "-q")
    r = grano.read("r.h5")
    with h5py.File("r.h5", "r") as f:
        ok = np.array_equal(r.observables["temperature"].to_numpy(), f["observables/temperature/value"][()])
        ok = ok and np.array_equal(r.observables[["momentum_x", "momentum_y"]].to_numpy(),
                                   f["observables/momentum/value"][()])
        ok = ok and np.array_equal(r.observables.index.to_numpy(), f["observables/temperature/time"][()])
        ok = ok and np.array_equal(r.trajectory.position, f["particles/trajectory/position/value"][()])
        ok = ok and np.array_equal(r.fields["packing_fraction"]["value"], f["fields/packing_fraction/value"][()])
    tap.check(ok and r.method == "dem" and r.seed == 1 and r.trajectory.box == (30.0, 30.0),
              "grano.read: observables as a DataFrame, trajectory and fields as arrays, as h5py reads them (%r)" % r)
    rc, err = cli(exe, "course", "maxwell", "--quick", "--out", "course", "--force")
    r = grano.read("course/maxwell.h5")
    d = r.results.get("maxwell/distance")
    tap.check(rc == 0 and d is not None and list(d.columns)[:2] == ["collisions_per_grain", "ks"] and len(d) == 5,
              "grano.read: a result table with columns as a DataFrame", err)
    with h5py.File("compare.h5", "w") as f:
        g = f.create_group("cases/collision", track_order=True)  # as grano compare writes it
        g["method"] = np.array(["dem", "edmd"], dtype=h5py.string_dtype())
        g["value"] = np.array([1.5, 2.5])
        g["runs"] = np.array([4, 4], dtype=np.int64)
    t = grano.read("compare.h5").tables.get("cases/collision")
    tap.check(t is not None and list(t.columns) == ["method", "value", "runs"] and list(t.method) == ["dem", "edmd"],
              "grano.read: a file of column tables (compare.h5's layout) as DataFrames")


def restarts(tap, grano, exe, root):
    ini = "%s/experiments/scenes/box.ini" % root
    cli(exe, "run", ini, "-m", "edmd", "--until", 0.5, "-o", "k.h5", "-f", "-q")
    a = grano.Sim.load("k.ckpt")
    b = grano.Sim.load("k.ckpt", scene=grano.Scene(ini).set("run.observe_every", 0.1))
    tap.check(a.method == "edmd" and a.time == 0.5 and "observe_every" in b.restart_notes,
              "Sim.load: the stored scene, method and seed; a scene whose [run] differs is noted (%s)"
              % b.restart_notes.strip())
    try:
        grano.Sim.load("k.ckpt", scene=grano.Scene(ini).set("material.mu", 0.2))
        msg = None
    except grano.SceneError as e:
        msg = str(e)
    c = grano.Sim.load("k.ckpt", scene=grano.Scene(ini).set("material.mu", 0.2), branch=True)
    tap.check(msg is not None and "--set material.mu" in msg and c.time == 0.5,
              "Sim.load: a physical change is refused naming it, and allowed with branch=True (%s)" % msg)


def main(argv):
    exe, root, work = setup(argv)
    import grano
    tap = Tap()
    refusals(tap, grano, exe, root)
    registry(tap, grano, exe)
    snapshots(tap, grano, root)
    failures(tap, grano, exe, root)
    interrupt(tap, grano, root)
    gil(tap, grano, root)
    reading(tap, grano, exe, root)
    restarts(tap, grano, exe, root)
    return tap.finish()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
