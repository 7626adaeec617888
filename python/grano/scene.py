"""grano.Scene: a scene file with settings applied as `--set` applies them,
or a dict of sections; read and checked by grano's own reader."""
import ctypes as C
import os

from . import _lib
from ._lib import lib


def _word(v):
    """A Python value as a scene file writes it."""
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, (list, tuple)):
        return " ".join(_word(x) for x in v)
    return repr(v) if isinstance(v, float) else str(v)


def _sections(d):
    """{"material": {"mu": 0.3}} or {"material.mu": 0.3}: section -> {key: value}."""
    out = {}
    for k, v in d.items():
        if isinstance(v, dict):
            out.setdefault(str(k), {}).update({str(a): b for a, b in v.items()})
        elif "." in str(k):
            sec, key = str(k).split(".", 1)
            out.setdefault(sec, {})[key] = v
        else:
            raise TypeError("scene dict: %r is neither a section (a dict) nor 'section.key'" % (k,))
    return out


class Scene:
    """A scene, from a file path or a dict of sections.

    Scene("experiments/scenes/box.ini") reads the file as `grano run` does;
    Scene({"domain": {"width": 30, ...}, "species": {"count": 100}}) reads
    the text made of the dict (true/false become yes/no, a list "nx ny").
    set("section.key", value) changes one key as `--set section.key=value`
    does. Every change is read and checked at once: a refusal raises
    grano.SceneError with grano's message, naming the file and line, or
    the setting ("--set material.mu: ..."), or the key.

    seed, when given, replaces [scene] seed as `--seed` does (the scene's
    text stays as written).
    """

    def __init__(self, source, seed=None):
        self._dict = None
        self._sets = []
        self._seed = None if seed is None else int(seed)
        if isinstance(source, Scene):
            self._path, self._dict, self._sets = source._path, source._dict, list(source._sets)
            self._seed = source._seed if seed is None else self._seed
        elif isinstance(source, dict):
            self._path, self._dict = "(dict)", _sections(source)
        elif isinstance(source, (str, os.PathLike)):
            self._path = os.fspath(source)
        else:
            raise TypeError("Scene: a path or a dict, not %s" % type(source).__name__)
        self._info = None
        self._check()

    def _text(self):
        lines = []
        for sec, keys in self._dict.items():
            lines.append("[%s]" % sec)
            lines += ["%s = %s" % (k, _word(v)) for k, v in keys.items()]
        return "\n".join(lines) + "\n"

    def _c(self):
        """A new C scene (the caller owns it)."""
        err = _lib.Err()
        if self._dict is not None:
            h = lib.gp_scene_parse(self._text().encode(), self._path.encode(), C.byref(err))
        else:
            arr, n = self._csets()
            h = lib.gp_scene_load(os.fsencode(self._path), arr, n, C.byref(err))
        if not h:
            _lib.check(err.code or 2, err)
        if self._seed is not None:
            lib.gp_scene_set_seed(h, self._seed)
        return h

    def _csets(self):
        """The settings as a C array and its length (for messages)."""
        sets = [s.encode() for s in self._sets]
        return (C.c_char_p * max(1, len(sets)))(*sets), len(sets)

    def _check(self):
        h = self._c()
        try:
            num = (C.c_double * 6)()
            lib.gp_scene_numbers(h, num)
            nx, ny = C.c_int(), C.c_int()
            lib.gp_scene_field_cells(h, C.byref(nx), C.byref(ny))
            self._info = {
                "text": _lib.s(lib.gp_scene_text(h)), "name": _lib.s(lib.gp_scene_name(h)),
                "seed": lib.gp_scene_seed(h), "until": num[0], "output_every": num[1],
                "observe_every": num[2], "checkpoint_every": num[3], "width": num[4],
                "height": num[5], "field_cells": (nx.value, ny.value) if nx.value > 0 else None,
            }
        finally:
            lib.gp_scene_free(h)

    def set(self, key, value):
        """Set section.key to value as --set does; returns the scene."""
        key = str(key)
        if "." not in key:
            raise ValueError("Scene.set: '%s': expected 'section.key' (e.g. 'material.mu')" % key)
        old = (self._dict, list(self._sets))
        if self._dict is not None:
            sec, k = key.split(".", 1)
            self._dict = {s: dict(kv) for s, kv in self._dict.items()}
            self._dict.setdefault(sec, {})[k] = value
        else:
            # the latest value of a key replaces the earlier setting
            self._sets = [s for s in self._sets if s.split("=", 1)[0] != key]
            self._sets.append("%s=%s" % (key, _word(value)))
        try:
            self._check()
        except Exception:
            self._dict, self._sets = old
            raise
        return self

    def copy(self):
        return Scene(self)

    def get(self, key, default=None):
        """The value of section.key as written in the text run, or default."""
        sec, k = str(key).split(".", 1)
        h = self._c()
        try:
            v = _lib.s(lib.gp_scene_value(h, sec.encode(), k.encode()))
        finally:
            lib.gp_scene_free(h)
        return default if v is None else v

    path = property(lambda self: self._path, doc="the file the scene was read from ('(dict)' for a dict)")
    text = property(lambda self: self._info["text"], doc="the text run: the file with the settings applied")
    name = property(lambda self: self._info["name"])
    until = property(lambda self: self._info["until"], doc="[run] until")
    observe_every = property(lambda self: self._info["observe_every"])
    output_every = property(lambda self: self._info["output_every"])
    checkpoint_every = property(lambda self: self._info["checkpoint_every"])
    box = property(lambda self: (self._info["width"], self._info["height"]), doc="(width, height)")
    field_cells = property(lambda self: self._info["field_cells"], doc="[measure] field_cells, or None")
    settings = property(lambda self: list(self._sets), doc="the settings applied, as --set lines")

    @property
    def seed(self):
        return self._info["seed"]

    @seed.setter
    def seed(self, value):
        self._seed = int(value)
        self._check()

    def __repr__(self):
        sets = "".join(" --set %s" % s for s in self._sets)
        return "<grano.Scene %s from %s%s, seed %d>" % (self.name, self._path, sets, self.seed)
