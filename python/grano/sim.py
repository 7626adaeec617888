"""grano.Sim: one method on one scene (gr_sim, methods/method.h), advanced
over the sample times of `grano run` so that its trajectory, observables
and checkpoints are the CLI's, bit for bit."""
import contextlib
import ctypes as C
import math
import os
import sys
import threading
import time as _time
import warnings
import weakref

import numpy as np

from . import _lib, errors, registry
from ._lib import lib, run
from .scene import Scene

# Wall time of one call into C between checks for Ctrl-C (KeyboardInterrupt
# is raised when a call returns, so this bounds how long it waits).
CHUNK_S = 0.1


class _Array:
    """A C array as NumPy sees it; holds the owner of the memory."""

    def __init__(self, owner, addr, n, typestr):
        self.owner = owner
        self.__array_interface__ = {"data": (addr, False), "shape": (n,), "typestr": typestr,
                                    "version": 3}


class _Particles:
    """Owns a gr_particles; freed when no snapshot or array needs it."""

    def __init__(self, ptr):
        self.ptr = ptr
        weakref.finalize(self, lib.gp_particles_free, ptr)


class Snapshot:
    """Every grain at time t, in id order (wall grains and grains gone
    included; flags tell them apart: 1 fixed, 2 gate, 4 gone).

    x, y, vx, vy, omega, radius, mass, inertia (float64), flags (uint32),
    id (int64) and species (int32) are NumPy views of the snapshot's own C
    arrays, without copies; they are writable, and changing them changes
    the state that Sim(..., init=snapshot) starts from, never the run the
    snapshot came from. positions and velocities are (n, 2) arrays made by
    copying, because grano stores x and y in separate arrays (a structure
    of arrays).
    """

    _NAMES = ("x", "y", "vx", "vy", "omega", "radius", "mass", "inertia", "flags", "id", "species")
    _TYPES = ("<f8",) * 8 + ("<u4", "<i8", "<i4")

    def __init__(self, ptr, t):
        self._p = _Particles(ptr)
        self.t = t
        n = lib.gp_particles_n(ptr)
        for k, (name, ts) in enumerate(zip(self._NAMES, self._TYPES)):
            addr = lib.gp_particles_data(ptr, k)
            a = np.asarray(_Array(self._p, addr, n, ts)) if n and addr else np.empty(0, ts)
            setattr(self, name, a)

    def __len__(self):
        return len(self.x)

    @property
    def positions(self):
        return np.column_stack((self.x, self.y))

    @property
    def velocities(self):
        return np.column_stack((self.vx, self.vy))

    @property
    def mobile(self):
        """Grains that move: not fixed, not a gate, not gone."""
        return (self.flags & 7) == 0

    def __repr__(self):
        return "<grano.Snapshot of %d grains at t = %g>" % (len(self), self.t)


class _Bar:
    """tqdm when installed, else a line on standard error."""

    def __init__(self, t0, t1):
        self.t0, self.t1, self.last, self.ended = t0, t1, t0, False
        try:
            from tqdm.auto import tqdm
            self.bar = tqdm(total=t1 - t0, unit="tau", unit_scale=True, leave=True)
        except ImportError:
            self.bar, self.shown = None, 0.0

    def update(self, t):
        if self.bar is not None:
            self.bar.update(t - self.last)
        elif _time.monotonic() - self.shown > 0.5 or (t >= self.t1 and not self.ended):
            self.shown, self.ended = _time.monotonic(), t >= self.t1
            frac = (t - self.t0) / (self.t1 - self.t0) if self.t1 > self.t0 else 1.0
            sys.stderr.write("\rgrano: t = %-10.6g %5.1f %%" % (t, 100 * frac))
            sys.stderr.flush()
        self.last = t

    def close(self):
        if self.bar is not None:
            self.bar.close()
        else:
            sys.stderr.write("\n")


class Sim:
    """A method on a scene: grano.Sim(scene, method="dem").

    scene is a grano.Scene, a path or a dict; seed replaces the scene's as
    --seed does; init (a Snapshot) gives the grains to start from instead
    of the scene's [init]. A refused scene raises grano.SceneError.

    advance(t) stops at every sample time of the scene's [run]
    (observe_every, output_every, checkpoint_every, counted from the start)
    and samples the observables there (history()), as `grano run` does, so
    a run of the same scene, seed and method gives the same numbers to the
    last bit. step() leaves that grid.
    """

    def __init__(self, scene, method="dem", seed=None, init=None, _handle=None):
        self._lock = threading.Lock()
        self._wbuf = C.create_string_buffer(8192)
        if _handle is not None:
            self._h = _handle
        else:
            scene = Scene(scene, seed=seed) if seed is not None or not isinstance(scene, Scene) else scene
            registry.method(method)
            if init is not None and not isinstance(init, Snapshot):
                raise TypeError("Sim: init is a grano.Snapshot")
            err = _lib.Err()
            h, (sets, n) = scene._c(), scene._csets()
            self._h = lib.gp_sim_create(str(method).encode(), h, sets, n,
                                        init._p.ptr if init is not None else None, C.byref(err))
            if not self._h:
                _lib.check(err.code or 2, err)
        self._free = weakref.finalize(self, lib.gp_sim_free, self._h)
        self.method = _lib.s(lib.gp_sim_method(self._h))
        self._m = registry.method(self.method)
        self.restart_notes = ""

    @classmethod
    def load(cls, path, scene=None, method=None, branch=False):
        """A checkpoint of grano run or Sim.save. Without scene, the scene,
        method and seed stored in it; with one, as grano run SCENE --restart
        (its [run] and [measure] may differ; anything with branch=True, as
        --branch). restart_notes lists what differed."""
        err = _lib.Err()
        notes = C.create_string_buffer(2048)
        scene = Scene(scene) if scene is not None else None
        sc, (sets, n) = (scene._c(), scene._csets()) if scene is not None else (None, (None, 0))
        h = lib.gp_sim_load(os.fsencode(path), sc, sets, n, None if method is None else str(method).encode(),
                            int(bool(branch)), notes, len(notes), C.byref(err))
        if not h:
            _lib.check(err.code or 2, err)
        s = cls(None, _handle=h)
        s.restart_notes = _lib.s(notes.value)
        return s

    def close(self):
        """Free the C state now (it is also freed when the Sim is collected)."""
        with self._busy():
            self._free()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    @contextlib.contextmanager
    def _busy(self):
        if not self._free.alive:
            raise ValueError("this grano.Sim is closed")
        if not self._lock.acquire(blocking=False):
            raise RuntimeError("this grano.Sim is busy in another thread")
        try:
            yield self._h
        finally:
            self._lock.release()

    @property
    def time(self):
        with self._busy() as h:
            return lib.gp_sim_time(h)

    @property
    def scene_text(self):
        with self._busy() as h:
            return _lib.s(lib.gp_scene_text(lib.gp_sim_scene(h)))

    def _warn(self, h):
        buf = self._wbuf
        if lib.gp_sim_warnings(h, buf, len(buf)):
            for line in _lib.s(buf.value).splitlines():
                warnings.warn(line, errors.ValidityWarning, stacklevel=3)

    def advance(self, t, progress=False):
        """Run to time t. The GIL is released while the method runs, in
        calls of about CHUNK_S seconds; Ctrl-C stops between two of them
        with KeyboardInterrupt, leaving a valid state at the time reached.
        A failed step raises grano.RunError with the method's diagnostic
        (the state is the last good one). progress: a bar (tqdm if
        installed). Returns self."""
        t = float(t)
        if not math.isfinite(t):
            raise ValueError("advance: t = %r is not a finite time" % t)
        with self._busy() as h:
            now = lib.gp_sim_time(h)
            if t < now - 1e-9 * max(1.0, abs(now)):
                raise ValueError("advance: t = %g is before the simulation's time %g" % (t, now))
            bar = _Bar(now, t) if progress else None
            err, done, steps = _lib.Err(), C.c_int(0), 16
            try:
                while not done.value:
                    w = _time.perf_counter()
                    rc = run.gp_sim_advance(h, t, steps, C.byref(done), C.byref(err))
                    w = _time.perf_counter() - w
                    self._warn(h)
                    _lib.check(rc, err, errors.RunError)
                    if bar:
                        bar.update(lib.gp_sim_time(h))
                    steps = steps * 2 if w < CHUNK_S / 4 else max(1, steps // 2) if w > CHUNK_S else steps
                    steps = min(steps, 1 << 40)
            finally:
                if bar:
                    bar.close()
        return self

    def step(self, n=1):
        """n steps (or events) of the method, off the sample times; in calls
        of about CHUNK_S seconds, as advance."""
        with self._busy() as h:
            err, left, chunk = _lib.Err(), int(n), 16
            while left > 0:
                k = min(left, chunk)
                w = _time.perf_counter()
                rc = run.gp_sim_step(h, k, C.byref(err))
                w = _time.perf_counter() - w
                self._warn(h)
                _lib.check(rc, err, errors.RunError)
                left -= k
                chunk = chunk * 2 if w < CHUNK_S / 4 else max(1, chunk // 2) if w > CHUNK_S else chunk
        return self

    def _raw(self):
        """One observation: t, steps, the doubles [2n], the counts [n], skip."""
        with self._busy() as h:
            n = len(self._m.observables)
            t, steps, skip = C.c_double(), C.c_uint64(), C.c_uint64()
            val, ival = np.empty(2 * n), np.zeros(n, np.int64)
            err = _lib.Err()
            _lib.check(lib.gp_sim_observe(h, C.byref(t), C.byref(steps),
                                          val.ctypes.data_as(C.POINTER(C.c_double)),
                                          ival.ctypes.data_as(C.POINTER(C.c_int64)), C.byref(skip),
                                          C.byref(err)), err)
            return t.value, steps.value, val, ival, skip.value

    def observables(self):
        """The method's declared observables now (those the scene has), by
        name: a float, a count (int) or an (x, y) tuple; also t and step (the
        method's step or event count, as a result file's step).
        Window averages (wall_pressure) cover the time since the last
        sample time."""
        t, steps, val, ival, skip = self._raw()
        out = {"t": t, "step": steps}
        for k, o in enumerate(self._m.observables):
            if (skip >> k) & 1:
                continue
            out[o.name] = (int(ival[k]) if o.kind == "count" else (float(val[2 * k]), float(val[2 * k + 1]))
                           if o.kind == "vector" else float(val[2 * k]))
        return out

    def history(self, clear=False):
        """The samples at the sample times so far (every observe_every), as
        grano run writes observables/: a pandas DataFrame indexed by time,
        with step and each observable (a vector as NAME_x, NAME_y). A
        sample due at the present time is included. clear: forget the
        samples returned."""
        import pandas
        with self._busy() as h:
            t, st = C.POINTER(C.c_double)(), C.POINTER(C.c_uint64)()
            dv, iv = C.POINTER(C.c_double)(), C.POINTER(C.c_int64)()
            rows = lib.gp_sim_history(h, C.byref(t), C.byref(st), C.byref(dv), C.byref(iv))
            n = len(self._m.observables)

            def rows_of(p, shape, dtype):
                return np.ctypeslib.as_array(p, shape).copy() if rows and shape[-1] else np.empty(shape, dtype)
            times, steps = rows_of(t, (rows,), np.float64), rows_of(st, (rows,), np.uint64)
            dvals, ivals = rows_of(dv, (rows, 2 * n), np.float64), rows_of(iv, (rows, n), np.int64)
            skip, due = lib.gp_sim_obs_skip(h), lib.gp_sim_sample_due(h)
            if clear:
                lib.gp_sim_history_clear(h)
        if due:
            now = self._raw()
            times, steps = np.append(times, now[0]), np.append(steps, np.uint64(now[1]))
            dvals, ivals = np.vstack((dvals, now[2])), np.vstack((ivals, now[3]))
        cols = {"step": steps}
        for k, o in enumerate(self._m.observables):
            if (skip >> k) & 1:
                continue
            if o.kind == "count":
                cols[o.name] = ivals[:, k]
            elif o.kind == "vector":
                cols[o.name + "_x"], cols[o.name + "_y"] = dvals[:, 2 * k], dvals[:, 2 * k + 1]
            else:
                cols[o.name] = dvals[:, 2 * k]
        return pandas.DataFrame(cols, index=pandas.Index(times, name="time"))

    def snapshot(self):
        """Every grain now (a grano.Snapshot); a lattice method has none
        and raises grano.SceneError naming the method."""
        with self._busy() as h:
            err = _lib.Err()
            p = lib.gp_sim_snapshot(h, C.byref(err))
            if not p:
                _lib.check(err.code or 1, err)
            return Snapshot(p, lib.gp_sim_time(h))

    def fields(self, cells=None):
        """Coarse-grained fields now on nx x ny cells over the domain (cells,
        else the scene's [measure] field_cells): packing_fraction [ny][nx],
        velocity [ny][nx][2], temperature [ny][nx], as fields/ in a result
        file, with origin and cell (the cell's size)."""
        with self._busy() as h:
            if cells is None:
                nx, ny = C.c_int(), C.c_int()
                lib.gp_scene_field_cells(lib.gp_sim_scene(h), C.byref(nx), C.byref(ny))
                if nx.value <= 0:
                    raise ValueError("fields: give cells=(nx, ny); the scene sets no [measure] field_cells")
                cells = (nx.value, ny.value)
            nx, ny = int(cells[0]), int(cells[1])
            phi, v, T = np.empty((ny, nx)), np.empty((ny, nx, 2)), np.empty((ny, nx))
            err = _lib.Err()
            pd = C.POINTER(C.c_double)
            _lib.check(lib.gp_sim_fields(h, nx, ny, phi.ctypes.data_as(pd), v.ctypes.data_as(pd),
                                         T.ctypes.data_as(pd), C.byref(err)), err)
            num = (C.c_double * 6)()
            lib.gp_scene_numbers(lib.gp_sim_scene(h), num)
        return {"packing_fraction": phi, "velocity": v, "temperature": T, "origin": (0.0, 0.0),
                "cell": (num[4] / nx, num[5] / ny)}

    def counters(self):
        """The method's event counts by name (steps or events, collisions...)."""
        with self._busy() as h:
            names, vals = (C.c_char_p * 16)(), (C.c_uint64 * 16)()
            n = lib.gp_sim_counters(h, names, vals, 16)
            return {_lib.s(names[i]): int(vals[i]) for i in range(n)}

    def save(self, path):
        """The checkpoint grano run writes at this time (the same bytes):
        grano run SCENE --restart PATH and Sim.load(PATH) continue it. As
        at any sample time of the CLI, the samples due now are taken first
        and window averages start again."""
        with self._busy() as h:
            err = _lib.Err()
            _lib.check(lib.gp_sim_save(h, os.fsencode(path), C.byref(err)), err)

    def __repr__(self):
        if not self._free.alive:
            return "<grano.Sim closed>"
        return "<grano.Sim %s at t = %g>" % (self.method, self.time)
