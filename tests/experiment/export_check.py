#!/usr/bin/env python3
"""grano export read back by ASE (Debian's python3-ase): the lammps-dump and
extxyz trajectories give the positions, velocities and radii of the H5MD
frames (to 1e-12; the text carries 17 digits); csv the same; and a frame
exported as a LAMMPS data file or an extxyz frame starts a run through
[init] kind = file at exactly that state (the new run's first frame).

usage: export_check.py GRANO SOURCE_ROOT WORKDIR
"""
import os
import subprocess
import sys

import h5py
import numpy as np

from tap import Tap, skip

TOL = 1e-12
TAP = Tap()
check = TAP.check


def grano(*args):
    r = subprocess.run([GRANO] + list(args), capture_output=True, text=True)
    if r.returncode:
        raise RuntimeError("grano %s: exit %d: %s" % (" ".join(args), r.returncode, r.stderr))
    return r


def frames(path):
    with h5py.File(path, "r") as f:
        tr = f["particles/trajectory"]
        return (tr["position/value"][:], tr["velocity/value"][:], tr["radius"][()] if tr["radius"].shape != ()
                else tr["radius"][()], tr["position/step"][:], tr["position/time"][:])


def close(a, b):
    return a.shape == b.shape and np.max(np.abs(a - b)) <= TOL


def main():
    global GRANO
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    GRANO, src, work = sys.argv[1:]
    try:
        import ase.io
    except ImportError:
        skip("python3-ase is not installed (./grano.sh deps installs it)")
    os.makedirs(work, exist_ok=True)
    h5 = os.path.join(work, "box.h5")
    # rotating frictional grains with walls, three frames
    grano("run", os.path.join(src, "experiments/scenes/box.ini"), "--until", "1", "--out", h5, "--force", "-q")
    pos, vel, rad, step, time = frames(h5)
    nf, npart = pos.shape[0], pos.shape[1]
    rad = np.broadcast_to(rad, (npart,)) if np.ndim(rad) <= 1 else rad

    dump = os.path.join(work, "box.lammpstrj")
    grano("export", h5, "--format", "lammps-dump", "--out", dump, "--force")
    images = ase.io.read(dump, index=":", format="lammps-dump-text")
    check(len(images) == nf, "lammps-dump: ASE reads %d frames" % nf, len(images))
    # ASE takes a dump in LAMMPS's metal units (it has no lj): undo its
    # velocity conversion (distances are the same in both)
    from ase.calculators.lammps import convert
    vs = convert(1.0, "velocity", "metal", "ASE")
    ok = all(close(im.get_positions()[:, :2], pos[k]) and close(im.get_velocities()[:, :2] / vs, vel[k])
             and np.all(im.get_positions()[:, 2] == 0) for k, im in enumerate(images))
    check(ok, "lammps-dump: ASE's positions and velocities are the H5MD's, z = 0")
    with open(dump) as f:
        lines = f.read().splitlines()
    cols = lines[8].split()[2:]
    rows = np.array([l.split() for l in lines[9:9 + npart]], dtype=float)
    check(close(rows[:, cols.index("radius")], np.asarray(rad, float)) and
          close(rows[:, cols.index("omegaz")], frames_omega(h5)[0]),
          "lammps-dump: radius and omegaz columns")

    xyz = os.path.join(work, "box.extxyz")
    grano("export", h5, "--format", "extxyz", "--frames", "1:", "--out", xyz, "--force")
    images = ase.io.read(xyz, index=":", format="extxyz")
    check(len(images) == nf - 1, "extxyz --frames 1: gives %d frames" % (nf - 1), len(images))
    ok = all(close(im.get_positions()[:, :2], pos[k + 1]) and close(im.get_velocities()[:, :2], vel[k + 1])
             and close(im.arrays["radius"], np.asarray(rad, float)) and im.info.get("Step") == step[k + 1]
             and abs(im.info.get("Time") - time[k + 1]) < TOL for k, im in enumerate(images))
    check(ok, "extxyz: ASE's positions, velocities, radii, Step and Time are the H5MD's")

    csv = os.path.join(work, "box.csv")
    grano("export", h5, "--format", "csv", "--frames", "-1", "--out", csv, "--force")
    t = np.genfromtxt(csv, delimiter=",", names=True)
    check(len(t) == npart and close(np.c_[t["x"], t["y"]], pos[-1]) and close(np.c_[t["vx"], t["vy"]], vel[-1]),
          "csv --frames -1: the last frame")

    r = subprocess.run([GRANO, "export", h5, "--format", "csv", "--out", csv], capture_output=True, text=True)
    check(r.returncode == 2 and "--force" in r.stderr, "an existing --out is refused without --force", r.stderr)
    r = subprocess.run([GRANO, "export", h5, "--format", "lammps-data", "--frames", "0:2"],
                       capture_output=True, text=True)
    check(r.returncode == 2 and "--frames" in r.stderr, "lammps-data takes one frame", r.stderr)

    # round trip: the last frame as a packing made elsewhere
    for fmt, name in (("lammps-data", "pack.data"), ("extxyz", "pack.extxyz")):
        path = os.path.join(work, name)
        grano("export", h5, "--format", fmt, "--frames", "-1", "--out", path, "--force")
        out = os.path.join(work, "again-%s.h5" % fmt)
        grano("run", os.path.join(src, "experiments/scenes/box.ini"), "--set", "init.kind=file",
              "--set", "init.file=" + path, "--set", "init.velocity=zero", "--until", "0.01", "--out", out,
              "--force", "-q")
        p2, v2, r2, _, _ = frames(out)
        w1, w2 = frames_omega(h5)[-1], frames_omega(out)[0]
        check(close(p2[0], pos[-1]) and close(v2[0], vel[-1]) and close(np.broadcast_to(r2, (npart,)),
                                                                        np.broadcast_to(rad, (npart,)))
              and close(w2, w1), "[init] kind = file reads a %s frame back exactly (x, v, radius, spin)" % fmt)
    return TAP.finish()


def frames_omega(path):
    with h5py.File(path, "r") as f:
        g = f["particles/trajectory"]
        return g["omega/value"][:] if "omega" in g else np.zeros(g["position/value"].shape[:2])


if __name__ == "__main__":
    sys.exit(main())
