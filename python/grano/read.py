"""grano.read(path): a result file (docs/output-format.md) in pandas and
NumPy, through h5py."""
import numpy as np


def _str(v):
    return v.decode() if isinstance(v, bytes) else v


class Trajectory:
    """particles/trajectory: time, step [F]; position, velocity [F][N][2];
    omega [F][N]; flags [F][N] (1 fixed, 2 gate, 4 gone); radius, mass,
    inertia, species, id [N], or [F][N] where they changed during the run;
    box (width, height), periodic (x, y). Read whole into memory."""

    def __init__(self, g):
        self.time = g["position/time"][()]
        self.step = g["position/step"][()]
        n = len(self.time)
        for name in ("position", "velocity", "omega", "flags"):
            setattr(self, name, g[name + "/value"][:n] if name in g else None)
        for name in ("radius", "mass", "inertia", "species", "id"):
            e = g.get(name)
            setattr(self, name, None if e is None else e[()] if hasattr(e, "shape") else e["value"][:n])
        self.box = tuple(g["box/edges/value"][-1]) if n else None
        self.periodic = tuple(_str(b).strip() == "periodic" for b in g["box"].attrs["boundary"])

    def __len__(self):
        return len(self.time)

    def __repr__(self):
        return "<grano trajectory: %d frames of %d grains>" % (len(self), self.position.shape[1] if len(self) else 0)


def _observables(g):
    import pandas
    cols, times = {}, None
    n = min(min(len(g[k]["time"]), len(g[k]["value"])) for k in g) if len(g) else 0
    for name in g:
        e = g[name]
        if times is None:
            times, cols["step"] = e["time"][:n], e["step"][:n]
        v = e["value"][:n]
        if v.ndim == 2:
            cols[name + "_x"], cols[name + "_y"] = v[:, 0], v[:, 1]
        else:
            cols[name] = v
    return pandas.DataFrame(cols, index=pandas.Index(times if times is not None else [], name="time"))


def _table(g):
    """A group of equal-length 1-D columns (compare.h5, silo-flow.h5), in
    the order written, as a DataFrame; None if it is not one."""
    import h5py
    import pandas
    items = list(g.items())
    if not items or not all(isinstance(d, h5py.Dataset) and d.ndim == 1 for _, d in items):
        return None
    if len({d.shape[0] for _, d in items}) != 1:
        return None
    return pandas.DataFrame({k: d.asstr()[()] if d.dtype.kind == "O" else d[()] for k, d in items})


def _result(d):
    """results/<name>: a 2-D table with its columns as a DataFrame, else an array."""
    import pandas
    v = d[()]
    cols = d.attrs.get("columns")
    if v.ndim == 2 and cols is not None and len(cols) == v.shape[1]:
        return pandas.DataFrame(v, columns=[_str(c) for c in cols])
    return v


class Result:
    """What a grano file holds.

    observables  pandas DataFrame indexed by time: step, each observable
                 (a vector as NAME_x, NAME_y); None without observables/
    trajectory   Trajectory (NumPy arrays), or None (a lattice run, a table file)
    fields       {name: {"time", "step", "value" [S][ny][nx](...), "origin", "cell"}}
    results      {name: DataFrame (a table with columns) or array}
    tables       {group: DataFrame} for files of column tables (grano compare's
                 cases/<case>, profiles/<case>/errors; silo-flow.h5 ...)
    contacts     DataFrame frame, time, i, j, fn, ft, or None
    scene, method, seed, version, attrs   from parameters/ and the root
    """

    def __init__(self, path):
        import h5py
        self.path = str(path)
        try:
            f = h5py.File(path, "r")
        except OSError:
            # a run writing it, or killed while it did: HDF5's SWMR read mode
            f = h5py.File(path, "r", swmr=True)
        with f:
            self.attrs = {k: _str(v) for k, v in f.attrs.items()}
            p = f.get("parameters")
            get = (lambda k: _str(p[k].asstr()[()]) if k in p else None) if p is not None else (lambda k: None)
            self.scene, self.method, self.version = get("scene"), get("method"), get("grano_version")
            self.seed = int(p["seed"][()]) if p is not None and "seed" in p else None
            traj = f.get("particles/trajectory")
            self.trajectory = Trajectory(traj) if traj is not None and "position" in traj else None
            self.observables = _observables(f["observables"]) if "observables" in f else None
            self.fields = {}
            for name, g in (f["fields"].items() if "fields" in f else []):
                self.fields[name] = {"time": g["time"][()], "step": g["step"][()], "value": g["value"][()],
                                     "origin": tuple(g.attrs["origin"]), "cell": tuple(g.attrs["cell"])}
            self.results = {}
            if "results" in f:
                f["results"].visititems(lambda k, d: self.results.__setitem__(k, _result(d))
                                        if isinstance(d, h5py.Dataset) else None)
            self.tables = {}

            def visit(k, g):
                if isinstance(g, h5py.Group) and not k.startswith(("particles", "observables", "fields",
                                                                     "results", "parameters", "checkpoint",
                                                                     "h5md", "contacts")):
                    t = _table(g)
                    if t is not None:
                        self.tables[k] = t
            f.visititems(visit)
            self.contacts = self._contacts(f["contacts"]) if "contacts" in f else None

    @staticmethod
    def _contacts(c):
        import pandas
        count = c["count"][()]
        frame = np.repeat(np.arange(len(count)), count)
        rows = int(count.sum())
        force = c["force"][:rows]
        return pandas.DataFrame({"frame": frame, "time": c["time"][()][frame], "i": c["i"][:rows],
                                 "j": c["j"][:rows], "fn": force[:, 0], "ft": force[:, 1]})

    def __repr__(self):
        parts = []
        if self.trajectory is not None:
            parts.append("%d frames" % len(self.trajectory))
        if self.observables is not None:
            parts.append("%d observable samples" % len(self.observables))
        for what in ("fields", "results", "tables"):
            if getattr(self, what):
                parts.append("%s %s" % (what, ", ".join(getattr(self, what))))
        return "<grano.Result %s: %s%s>" % (self.path, self.method + ", " if self.method else "",
                                           "; ".join(parts) or "empty")


def read(path):
    """grano.read("results/box-edmd.h5"): a Result (see its doc)."""
    return Result(path)
