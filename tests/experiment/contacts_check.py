#!/usr/bin/env python3
"""`[run] contacts = yes` through `grano run`: the contact network written
with each frame (contacts/ of the result file) holds, for a resting column
of N frictionless disks solved by contact dynamics, the statics exactly:
the contact below disk k carries the weight of the N - k disks above it
(forces (1..N) m g, to the solver tolerance), with no tangential force;
a method without contact networks is refused up front, naming the line.

usage: contacts_check.py GRANO WORKDIR
"""
import os
import subprocess
import sys

import h5py
import numpy as np

SCENE = """[scene]
name = column
seed = 1
[domain]
width = 1.3
height = 14
gravity = 1
[material]
restitution = 0
mu = 0
[species]
count = %d
[init]
kind = lattice
region = 0 0 1.3 12
velocity = zero
[cd]
tol = 1e-10
[run]
until = 1.5
output_every = 0.5
contacts = yes
"""


def check(cond, what):
    print(("ok - " if cond else "not ok - ") + what)
    return 0 if cond else 1


def main(argv):
    grano, work = argv[1], argv[2]
    os.makedirs(work, exist_ok=True)
    n = 10
    scene = os.path.join(work, "column.ini")
    with open(scene, "w") as f:
        f.write(SCENE % n)
    out = os.path.join(work, "column.h5")
    r = subprocess.run([grano, "run", scene, "--method", "cd", "--out", out, "--force", "-q"],
                       capture_output=True, text=True)
    bad = check(r.returncode == 0, "cd runs the column (%s)" % r.stderr.strip())
    if r.returncode:
        return 1
    with h5py.File(out, "r") as h:
        c = h["contacts"]
        count = c["count"][:]
        bad += check(len(count) == len(h["particles/trajectory/position/time"]),
                     "one network per frame (%d)" % len(count))
        first = int(count[:-1].sum())
        last = slice(first, first + int(count[-1]))
        fn, ft = c["force"][last, 0], c["force"][last, 1]
        i, j = c["i"][last], c["j"][last]
        bad += check(c["force"].attrs["unit"] in (b"m d tau-2", "m d tau-2"), "force unit m d tau-2")
    want = np.arange(1, n + 1, dtype=float)
    got = np.sort(fn)
    bad += check(len(fn) == n and np.allclose(got, want, rtol=1e-6, atol=0),
                 "normal forces %s are (1..%d) m g to 1e-6" % (np.round(got, 9).tolist(), n))
    bad += check(len(ft) and np.abs(ft).max() < 1e-9, "no tangential force (frictionless)")
    bad += check(int((j < 0).sum()) == 1 and fn[j < 0][0] == fn.max(),
                 "one wall contact, the floor, carries the whole weight")
    bad += check(sorted(set(i.tolist()) | set(j[j >= 0].tolist())) == list(range(n)),
                 "the network joins every disk")
    refused = os.path.join(work, "refused.h5")
    r = subprocess.run([grano, "run", scene, "--method", "edmd", "--out", refused, "--force", "-q"],
                       capture_output=True, text=True)
    line = (SCENE % n).splitlines().index("contacts = yes") + 1
    bad += check(r.returncode == 2 and "column.ini:%d:" % line in r.stderr and "contact networks" in r.stderr
                 and not os.path.exists(refused),
                 "edmd (no contact networks) refused up front, naming the line: %s" % r.stderr.strip())
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
