#!/usr/bin/env python3
"""What MDAnalysis (Debian's python3-mdanalysis, when installed; skipped
otherwise) makes of grano's files, as docs/output-format.md states it:
the H5MD result is refused (MDAnalysis reads only 3-D H5MD boxes; should a
later version take it, this test says so and the docs must change), while
the `grano export` lammps-dump trajectory and lammps-data frame are read:
x, y to float32 precision, every frame; the dump's z is 0.5, MDAnalysis
putting the origin at the box's lower corner (z from -0.5 to 0.5).

usage: mdanalysis_check.py GRANO SOURCE_ROOT WORKDIR
"""
import os
import subprocess
import sys
import warnings

import h5py
import numpy as np

from tap import Tap, skip


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    grano, src, work = sys.argv[1:]
    try:
        import MDAnalysis as mda
    except ImportError:
        skip("python3-mdanalysis is not installed (optional: apt-get install python3-mdanalysis)")
    warnings.simplefilter("ignore")
    tap = Tap()
    os.makedirs(work, exist_ok=True)
    h5 = os.path.join(work, "box.h5")
    run = lambda *a: subprocess.run([grano] + list(a), check=True, capture_output=True)
    run("run", os.path.join(src, "experiments/scenes/box.ini"), "--until", "1", "--out", h5, "--force", "-q")
    with h5py.File(h5, "r") as f:
        pos = f["particles/trajectory/position/value"][:]
    try:
        from MDAnalysis.coordinates.H5MD import H5MDReader
        H5MDReader(h5, convert_units=False)
        tap.check(False, "MDAnalysis %s now reads a 2-D H5MD file: update docs/output-format.md" % mda.__version__)
    except ValueError as e:
        tap.check("3-dimensional" in str(e), "MDAnalysis %s refuses the 2-D H5MD box, as documented" % mda.__version__,
                  e)
    dump = os.path.join(work, "box.lammpstrj")
    run("export", h5, "--format", "lammps-dump", "--out", dump, "--force")
    u = mda.Universe(dump, format="LAMMPSDUMP")
    ok = len(u.trajectory) == len(pos) and all(
        np.allclose(ts.positions[:, :2], pos[k], atol=1e-5) and np.all(ts.positions[:, 2] == 0.5)
        for k, ts in enumerate(u.trajectory))
    tap.check(ok, "MDAnalysis reads the lammps-dump export: %d frames, x and y, z = 0.5" % len(pos))
    data = os.path.join(work, "pack.data")
    run("export", h5, "--format", "lammps-data", "--out", data, "--force")
    u = mda.Universe(data, atom_style="id type diameter density x y z")
    tap.check(np.allclose(u.atoms.positions[:, :2], pos[-1], atol=1e-5),
              "MDAnalysis reads the lammps-data export (atom_style 'id type diameter density x y z')")
    return tap.finish()


if __name__ == "__main__":
    sys.exit(main())
