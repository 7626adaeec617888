"""grano from Python: the scenes, methods and results of the grano program
(docs/python.md).

    import grano
    sim = grano.Sim(grano.Scene("experiments/scenes/box.ini"), method="edmd")
    sim.advance(1.0)
    sim.observables()["temperature"]

Scene (a file or a dict, set() as --set), Sim (advance, step, observables,
history, snapshot, fields, counters, save, Sim.load), methods() (the
registry), read() (a result file as DataFrames and arrays). Errors:
SceneError (bad input, with grano's message), RunError (a failed run);
ValidityWarning for a validity limit broken during a run.
"""
from ._lib import PATH as library
from ._lib import lib as _clib
from .errors import Error, RunError, SceneError, ValidityWarning
from .read import Result, Trajectory, read
from .registry import Method, Observable, Param, method, methods
from .scene import Scene
from .sim import Sim, Snapshot

__version__ = _clib.gp_version().decode()
__all__ = ["Error", "Method", "Observable", "Param", "Result", "RunError", "Scene", "SceneError", "Sim",
           "Snapshot", "Trajectory", "ValidityWarning", "library", "method", "methods", "read"]
