"""libgrano.so through ctypes: the flat interface of python/grano_py.h.

Two handles on one library: `run` calls release the GIL (ctypes.CDLL), for
the calls that advance a method and touch nothing but its state; `lib`
calls keep it (ctypes.PyDLL), for every call that may reach HDF5, which
h5py in another thread may be using and which is not built thread-safe.
"""
import ctypes as C
import os

from . import errors


class Err(C.Structure):
    _fields_ = [("code", C.c_int), ("msg", C.c_char * 1024)]


def _path():
    env = os.environ.get("GRANO_LIB")
    if env:
        return env
    return os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "libgrano.so")


_P, _D, _U64, _I, _S = C.c_void_p, C.c_double, C.c_uint64, C.c_int, C.c_char_p
_SZ, _E = C.c_size_t, C.POINTER(Err)
_PD, _PS = C.POINTER(C.c_double), C.POINTER(C.c_char_p)

# name: (restype, argtypes), on both handles.
_DECL = {
    "gp_init": (None, []),
    "gp_version": (_S, []),
    "gp_scene_load": (_P, [_S, _PS, _SZ, _E]),
    "gp_scene_parse": (_P, [_S, _S, _E]),
    "gp_scene_free": (None, [_P]),
    "gp_scene_text": (_S, [_P]),
    "gp_scene_path": (_S, [_P]),
    "gp_scene_name": (_S, [_P]),
    "gp_scene_seed": (_U64, [_P]),
    "gp_scene_set_seed": (None, [_P, _U64]),
    "gp_scene_numbers": (None, [_P, _PD]),
    "gp_scene_field_cells": (None, [_P, C.POINTER(_I), C.POINTER(_I)]),
    "gp_scene_value": (_S, [_P, _S, _S]),
    "gp_method_count": (_I, []),
    "gp_method_name": (_S, [_I]),
    "gp_method_summary": (_S, [_I]),
    "gp_method_repr": (_I, [_I]),
    "gp_method_features": (C.c_uint, [_I]),
    "gp_method_ops": (C.c_uint, [_I]),
    "gp_feature_count": (_I, []),
    "gp_op_count": (_I, []),
    "gp_feature_name": (_S, [C.c_uint]),
    "gp_feature_known": (_I, [C.c_uint]),
    "gp_op_name": (_S, [C.c_uint]),
    "gp_param_count": (_I, [_I]),
    "gp_param": (_S, [_I, _I, C.POINTER(_I), _PD, _PS, _PS]),
    "gp_param_choice": (_S, [_I, _I, _I]),
    "gp_obs_count": (_I, [_I]),
    "gp_obs": (_S, [_I, _I, _PS, C.POINTER(_I), C.POINTER(_I), _PS, _PS]),
    "gp_sim_create": (_P, [_S, _P, _PS, _SZ, _P, _E]),
    "gp_sim_load": (_P, [_S, _P, _PS, _SZ, _S, _I, C.c_char_p, _SZ, _E]),
    "gp_sim_free": (None, [_P]),
    "gp_sim_method": (_S, [_P]),
    "gp_sim_method_index": (_I, [_P]),
    "gp_sim_scene": (_P, [_P]),
    "gp_sim_time": (_D, [_P]),
    "gp_sim_advance": (_I, [_P, _D, _U64, C.POINTER(_I), _E]),
    "gp_sim_step": (_I, [_P, _U64, _E]),
    "gp_sim_observe": (_I, [_P, _PD, C.POINTER(_U64), _PD, C.POINTER(C.c_int64), C.POINTER(_U64), _E]),
    "gp_sim_history": (_SZ, [_P, C.POINTER(_PD), C.POINTER(C.POINTER(_U64)), C.POINTER(_PD),
                             C.POINTER(C.POINTER(C.c_int64))]),
    "gp_sim_history_clear": (None, [_P]),
    "gp_sim_obs_skip": (_U64, [_P]),
    "gp_sim_sample_due": (_I, [_P]),
    "gp_sim_snapshot": (_P, [_P, _E]),
    "gp_sim_fields": (_I, [_P, _I, _I, _PD, _PD, _PD, _E]),
    "gp_sim_counters": (_SZ, [_P, _PS, C.POINTER(_U64), _SZ]),
    "gp_sim_warnings": (_SZ, [_P, C.c_char_p, _SZ]),
    "gp_sim_save": (_I, [_P, _S, _E]),
    "gp_particles_n": (_SZ, [_P]),
    "gp_particles_data": (_P, [_P, _I]),
    "gp_particles_free": (None, [_P]),
}


def _load():
    path = _path()
    if not os.path.exists(path):
        raise ImportError("grano: %s not found: build grano (./grano.sh build) and put "
                          "<build>/python on PYTHONPATH, or set GRANO_LIB to libgrano.so" % path)
    held, free = C.PyDLL(path), C.CDLL(path)
    for name, (res, args) in _DECL.items():
        for h in (held, free):
            f = getattr(h, name)
            f.restype, f.argtypes = res, args
    return held, free


lib, run = _load()
lib.gp_init()
PATH = _path()


def s(b):
    """A C string as str (None stays None)."""
    return None if b is None else b.decode("utf-8", "replace")


def check(rc, err, cls=None):
    """Raise the gr_err as a grano error: bad input (GR_EINPUT) as
    SceneError unless told otherwise, a failed run as RunError."""
    if rc:
        msg = s(err.msg) or "failed (code %d)" % err.code
        if cls is None:
            cls = errors.SceneError if err.code == 2 else errors.RunError
        raise cls(msg)
