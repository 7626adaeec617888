#!/usr/bin/env python3
"""The same start on every method: a bed settled by the soft DEM, exported
as a LAMMPS data file, starts edmd. Without [init] overlap the hard disks
refuse it naming the file, the grain, the overlap (as the file has it) and
the key; with overlap = push no pair overlaps and no grain cuts a wall,
the run says the largest overlap and displacement (the same as measured
here), and the bed comes to rest on edmd, cd and dsmc. A file whose
overlap is beyond a soft packing's is refused by name.

usage: start_check.py GRANO WORKDIR
"""
import os
import re
import subprocess
import sys

import h5py
import numpy as np

from tap import Tap

TAP = Tap()
check = TAP.check
W, H = 10.37, 30.0  # a width no row of unit grains spans exactly

BED = """[scene]
name = bed
[domain]
width = %g
height = %g
gravity = 1
[material]
kn = 1e3
restitution = 0.3
[species]
count = 150
[init]
kind = random
velocity = gaussian
v0 = 1
[dem]
dt = 1e-3
[run]
until = 40
output_every = 10
""" % (W, H)

HARD = """[scene]
name = hard
[domain]
width = %g
height = %g
gravity = 1
[material]
restitution = 0.3
[init]
kind = file
file = %s
%s[edmd]
collapse = sleep
[run]
until = %g
output_every = 0.5
"""


def run(*args):
    return subprocess.run([GRANO] + list(args), capture_output=True, text=True)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)
    return path


def overlaps(xy, r):
    """Largest pair overlap, its grains (from 1), and the deepest wall cut."""
    d = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
    ov = r[:, None] + r[None, :] - d
    np.fill_diagonal(ov, -np.inf)
    i, j = np.unravel_index(np.argmax(ov), ov.shape)
    cut = np.max(np.c_[r - xy[:, 0], xy[:, 0] - (W - r), r - xy[:, 1], xy[:, 1] - (H - r)])
    return ov[i, j], (min(i, j) + 1, max(i, j) + 1), cut


def first_last(path):
    with h5py.File(path, "r") as f:
        tr = f["particles/trajectory"]
        pos, rad = tr["position/value"], tr["radius"][()]
        obs = f["observables"]
        e = obs["ekin_trans/value"][:] + obs["epot_grav/value"][:]
        note = f["parameters/derived"][()].decode() if "derived" in f["parameters"] else ""
        return pos[0][:, :2], pos[-1][:, :2], np.broadcast_to(rad, pos.shape[1:2]), e, note


def main():
    global GRANO
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    GRANO, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    bed, data = os.path.join(work, "bed.h5"), os.path.join(work, "bed.data")
    r = run("run", write(os.path.join(work, "bed.ini"), BED), "--method", "dem", "--out", bed, "--force", "-q")
    r = r if r.returncode else run("export", bed, "--format", "lammps-data", "--out", data, "--force")
    if r.returncode:
        check(False, "a dem bed settled and exported", r.stderr)
        return TAP.finish()
    rows = np.loadtxt(data, skiprows=11, max_rows=150)
    xy0, r0 = rows[:, 4:6], rows[:, 2] / 2
    ov0, pair0, cut0 = overlaps(xy0, r0)
    print("# the dem bed: largest overlap %.4g (grains %d and %d), deepest wall cut %.4g" % (ov0, *pair0, cut0))

    ini = write(os.path.join(work, "refuse.ini"), HARD % (W, H, data, "", 0.5))
    out = os.path.join(work, "refuse.h5")
    r = run("run", ini, "--method", "edmd", "--out", out, "--force", "-q")
    m = re.search(r"refuse\.ini:11: \[init\] key 'file': '.*bed\.data', grains counted from 1 in its order: grains (\d+) and (\d+) overlap by ([0-9.e+-]+) "
                  r".*; grain \d+ at .* cuts the .* by ([0-9.e+-]+) .*\[init\] overlap = push", r.stderr)
    named = m and (int(m.group(1)), int(m.group(2))) == pair0 and float(m.group(3)) == float("%.4g" % ov0) \
        and float(m.group(4)) == float("%.4g" % cut0)
    check(r.returncode == 2 and bool(named) and not os.path.exists(out),
          "edmd refuses the soft packing naming the file, the deepest overlaps (pair and wall) and the key", r.stderr)

    ini = write(os.path.join(work, "push.ini"), HARD % (W, H, data, "overlap = push\n", 2.0))
    out = os.path.join(work, "push.h5")
    r = run("run", ini, "--method", "edmd", "--out", out, "--force", "-q")
    if r.returncode:
        check(False, "edmd runs the pushed packing", r.stderr)
        return TAP.finish()
    xy1, xyn, rad, e, note = first_last(out)
    ov1, _, cut1 = overlaps(xy1, rad)
    disp = np.max(np.hypot(*(xy1 - xy0).T))
    height = np.max(xy0[:, 1] + r0)
    m = re.search(r"largest overlap ([0-9.e+-]+) .* largest displacement ([0-9.e+-]+)", note)
    print("# pushed: overlap %.3g, wall cut %.3g, largest displacement %.4g (%.1f largest overlaps, "
          "bed height %.2f d); edmd energy %.6g -> %.6g" % (ov1, cut1, disp, disp / ov0, height, e[0], e[-1]))
    check(ov1 <= 1e-9 and cut1 <= 1e-9, "after the push no pair overlaps and no grain cuts a wall",
          "%g %g" % (ov1, cut1))
    check(bool(m) and abs(float(m.group(1)) - ov0) <= 1e-4 * ov0 and abs(float(m.group(2)) - disp) <= 1e-4 * disp,
          "the run says the file's largest overlap and the largest displacement", note)
    # The rigid bed grows by its elastic compression: a grain moves at most
    # the overlaps of the contacts below it, one per row of the bed.
    r = run("info", out)
    check("derived      [init] overlap = push: largest overlap" in r.stdout, "grano info shows what the push did",
          r.stdout)
    check(0 < disp <= 2 * height * ov0, "the largest displacement is within the bed's compression "
          "(2 x height x largest overlap)", "%g" % disp)
    check(np.all(np.diff(e) <= 1e-9 * e[0]) and e[-1] < e[0] and np.max(np.abs(xyn - xy1)) < 0.05,
          "the bed stays at rest on edmd: energy never grows, no grain moves 0.05 d", "%s" % e)
    for m_ in ("cd", "dsmc", "dem"):
        r = run("run", ini, "--method", m_, "--until", "0.2", "--out", os.path.join(work, "push-%s.h5" % m_),
                "--force", "-q")
        check(r.returncode == 0, "the pushed packing starts %s" % m_, r.stderr)

    far = write(os.path.join(work, "far.txt"), "3 3\n3.7 3\n")
    ini = write(os.path.join(work, "far.ini"), HARD % (W, H, far, "overlap = push\n", 0.5))
    r = run("run", ini, "--method", "edmd", "--out", os.path.join(work, "far.h5"), "--force", "-q")
    check(r.returncode == 2 and "far.ini:12: [init] key 'overlap'" in r.stderr and "far.txt" in r.stderr
          and "grains 1 and 2" in r.stderr and "overlap by 0.3" in r.stderr,
          "an overlap beyond a soft packing's is refused naming the file, grains, overlap and key", r.stderr)
    return TAP.finish()


if __name__ == "__main__":
    sys.exit(main())
