"""grano.methods(): the registry (methods/registry.c) as `grano methods`
prints it: features, operations, observables and parameter tables."""
import ctypes as C
from dataclasses import dataclass, field

from . import _lib
from ._lib import lib

_TYPES = ("real", "int", "choice")


@dataclass(frozen=True)
class Observable:
    name: str
    unit: str
    kind: str          # "scalar", "vector" (x, y) or "count"
    doc: str
    key: str = None    # a validity limit's counter: the scene key that changes the limit


@dataclass(frozen=True)
class Param:
    name: str
    type: str          # "real", "int" or "choice"
    default: object    # a number, a choice's word, or None: derived from the scene
    min: float
    max: float
    min_open: bool
    unit: str
    doc: str
    choices: tuple = ()


@dataclass(frozen=True)
class Method:
    name: str
    summary: str
    representation: str            # "particles" or "lattice"
    features: tuple                # scene features it supports
    unsupported: tuple             # those it refuses
    operations: tuple              # optional operations of its own
    observables: tuple = field(repr=False)
    params: tuple = field(repr=False)

    def parameter_table(self):
        """The [name] section's keys as a pandas DataFrame."""
        import pandas
        return pandas.DataFrame([p.__dict__ for p in self.params]).set_index("name")

    def observable_table(self):
        import pandas
        return pandas.DataFrame([o.__dict__ for o in self.observables]).set_index("name")

    def __str__(self):
        lines = ["%s: %s" % (self.name, self.summary),
                 "  represents: %s" % self.representation,
                 "  features: %s" % "; ".join(self.features),
                 "  not supported: %s" % ("; ".join(self.unsupported) or "none"),
                 "  operations of its own: %s" % "; ".join(self.operations),
                 "  observables: %s" % ", ".join(o.name for o in self.observables),
                 "  [%s] parameters:" % self.name]
        for p in self.params:
            d = "(from the scene)" if p.default is None else p.default
            lines.append("    %-14s %-6s %-10s %s" % (p.name, p.type, d, p.doc))
        return "\n".join(lines)


def _bits(mask, count, name, known=None):
    return tuple(_lib.s(name(1 << b)) for b in range(count)
                 if (mask >> b) & 1 and (known is None or known(1 << b)))


def _method(i):
    feats = lib.gp_method_features(i)
    nfeat = lib.gp_feature_count()
    known = lib.gp_feature_known
    obs = []
    for k in range(lib.gp_obs_count(i)):
        unit, doc, key = C.c_char_p(), C.c_char_p(), C.c_char_p()
        nc, integer = C.c_int(), C.c_int()
        name = lib.gp_obs(i, k, C.byref(unit), C.byref(nc), C.byref(integer), C.byref(doc), C.byref(key))
        kind = "count" if integer.value else "vector" if nc.value == 2 else "scalar"
        obs.append(Observable(_lib.s(name), _lib.s(unit.value), kind, _lib.s(doc.value), _lib.s(key.value)))
    params = []
    for k in range(lib.gp_param_count(i)):
        t, v = C.c_int(), (C.c_double * 4)()
        unit, doc = C.c_char_p(), C.c_char_p()
        name = lib.gp_param(i, k, C.byref(t), v, C.byref(unit), C.byref(doc))
        choices = []
        while True:
            w = lib.gp_param_choice(i, k, len(choices))
            if w is None:
                break
            choices.append(_lib.s(w))
        d = v[0]
        default = None if d != d else choices[int(d)] if t.value == 2 else int(d) if t.value == 1 else d
        params.append(Param(_lib.s(name), _TYPES[t.value], default, v[1], v[2], bool(v[3]),
                            _lib.s(unit.value), _lib.s(doc.value), tuple(choices)))
    return Method(
        name=_lib.s(lib.gp_method_name(i)), summary=_lib.s(lib.gp_method_summary(i)),
        representation="lattice" if lib.gp_method_repr(i) else "particles",
        features=_bits(feats, nfeat, lib.gp_feature_name, known),
        unsupported=_bits(~feats, nfeat, lib.gp_feature_name, known),
        operations=_bits(lib.gp_method_ops(i), lib.gp_op_count(), lib.gp_op_name),
        observables=tuple(obs), params=tuple(params))


_ALL = {}


def methods():
    """Every registered method by name: grano.methods()["dem"].params ..."""
    if not _ALL:
        for i in range(lib.gp_method_count()):
            m = _method(i)
            _ALL[m.name] = m
    return dict(_ALL)


def method(name):
    """One method; an unknown name raises ValueError listing the others."""
    all_ = methods()
    if name not in all_:
        import difflib
        near = difflib.get_close_matches(str(name), list(all_), 1)
        hint = "; did you mean '%s'?" % near[0] if near else ""
        raise ValueError("unknown method '%s'%s (methods: %s)" % (name, hint, ", ".join(all_)))
    return all_[name]
