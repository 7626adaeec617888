#!/usr/bin/python3
"""Two HDF5 files hold the same objects with the same shapes, values (NaN
equal to NaN) and attributes; with paths, only under those. h5diff is no
judge of this: it exits 0 for datasets of different shapes ("not
comparable"). Opens a file still marked as being written (SWMR read).
Exit 0 if the same, 1 listing the first differences.
Usage: same_h5.py A B [PATH...]"""
import sys

import h5py
import numpy


def open_ro(path):
    try:
        return h5py.File(path, "r")
    except OSError:
        return h5py.File(path, "r", swmr=True)


def same_values(a, b):
    a, b = numpy.asarray(a), numpy.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    nan = a.dtype.kind in "fc"
    return numpy.array_equal(a, b, equal_nan=nan)


def objects(f, roots):
    out = {}
    for root in roots:
        if root != "/" and root not in f:
            continue  # absent here: what the other file holds under it is 'only in'
        g = f[root] if root != "/" else f
        if isinstance(g, h5py.Dataset):
            out[root.strip("/")] = g
            continue
        out[root.strip("/")] = g
        g.visititems(lambda k, o: out.__setitem__((root.strip("/") + "/" + k).strip("/"), o))
    return out


def diff(a_path, b_path, roots):
    bad = []
    with open_ro(a_path) as a, open_ro(b_path) as b:
        oa, ob = objects(a, roots), objects(b, roots)
        for name in sorted(set(oa) | set(ob)):
            if name not in oa or name not in ob:
                bad.append("%s: only in %s" % (name or "/", a_path if name in oa else b_path))
                continue
            x, y = oa[name], ob[name]
            if isinstance(x, h5py.Dataset) != isinstance(y, h5py.Dataset):
                bad.append("%s: a dataset in one file only" % name)
                continue
            if isinstance(x, h5py.Dataset):
                if x.shape != y.shape:
                    bad.append("%s: shape %s against %s" % (name, x.shape, y.shape))
                elif not same_values(x[()], y[()]):
                    bad.append("%s: values differ" % name)
            if set(x.attrs) != set(y.attrs):
                bad.append("%s: attributes %s against %s" % (name, sorted(x.attrs), sorted(y.attrs)))
            else:
                bad += ["%s: attribute %s differs" % (name, k) for k in x.attrs
                        if not same_values(x.attrs[k], y.attrs[k])]
    return bad


def main():
    if len(sys.argv) < 3:
        print(__doc__, file=sys.stderr)
        return 2
    bad = diff(sys.argv[1], sys.argv[2], sys.argv[3:] or ["/"])
    for line in bad[:20]:
        print(line)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
