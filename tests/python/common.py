"""What the Python module's tests share: TAP output (tests/experiment/tap.py),
the grano program and the source root from the arguments, a scratch
folder, a CLI run, and a comparison of two HDF5 files bit for bit."""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "experiment"))
from tap import Tap, skip  # noqa: E402,F401


def setup(argv):
    """argv: GRANO SOURCE_ROOT WORKDIR -> (grano, root, work), cwd = work."""
    if len(argv) < 4:
        sys.exit("usage: %s GRANO SOURCE_ROOT WORKDIR" % argv[0])
    grano_exe, root, work = (os.path.abspath(a) for a in argv[1:4])
    os.makedirs(work, exist_ok=True)
    os.chdir(work)
    try:
        import grano  # noqa: F401
    except ImportError as e:
        skip("grano not importable (%s)" % e)
    return grano_exe, root, work


def cli(grano_exe, *args):
    """grano ARGS; returns (exit code, stderr)."""
    r = subprocess.run([grano_exe] + [str(a) for a in args], capture_output=True, text=True)
    return r.returncode, r.stderr


def h5_diffs(a, b):
    """Members, datasets (type, shape, bytes) and attributes of a that
    differ from b's; [] when every one is the same bits. HDF5's own object
    modification times, which are not data, are not compared."""
    import h5py
    import numpy as np
    out = []
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        na, nb = [], []
        fa.visit(na.append)
        fb.visit(nb.append)
        if sorted(na) != sorted(nb):
            return ["members %s" % sorted(set(na) ^ set(nb))]
        for name in [None] + na:
            oa, ob = (fa, fb) if name is None else (fa[name], fb[name])
            if isinstance(oa, h5py.Dataset):
                va, vb = np.asarray(oa[()]), np.asarray(ob[()])
                if oa.dtype != ob.dtype or va.shape != vb.shape or va.tobytes() != vb.tobytes():
                    out.append(name)
            for k in set(oa.attrs) | set(ob.attrs):
                if k not in oa.attrs or k not in ob.attrs or \
                        np.asarray(oa.attrs[k]).tobytes() != np.asarray(ob.attrs[k]).tobytes():
                    out.append("%s@%s" % (name or "/", k))
    return out
