#!/usr/bin/env python3
"""[run] stress = yes against a static analytic case: a square stack of
10 x 10 frictionless unit disks (m = 1) on a floor between walls 10 d
apart under g = 1. Every contact is vertical, so sigma_xx = sigma_xy = 0;
the cell of row k (centres at y = k + 1/2, cells 1 d tall) carries
sigma_yy = (9.5 - k) m g / d^2, the weight above its middle over the width
(hydrostatic, no wall friction); and over the domain, at static
equilibrium, sigma_yy A = sum m g y (the virial identity, the floor
at y = 0). Contact dynamics is rigid: to 1e-9. Soft DEM (k_n = 1e5)
compresses each contact by about 1e-4 d, which shortens the levers: cells
to 1e-3, the identity (which holds with the actual levers) to 1e-5.
Methods with instantaneous collisions (edmd, dsmc) write the window-
averaged stress instead (kinetic plus collisional): on a periodic gas of
elastic disks at packing fraction 0.3, the first frame (an empty window)
holds NaN, the later ones Z = (sigma_xx + sigma_yy) / (2 n T) within 3 %
of the hard-disk equation of state (Luding's for edmd, Henderson's for
dsmc's Enskog mode, whose own tests hold 1 % and 2% on longer runs),
sigma_xy under 5 % of P, and the domain's value the mean of the cells to
1e-12. The lattice gas writes the kinetic stress of its particles (its
collisions move no momentum across space): on a periodic granular lattice
gas without dissipation, where the movers and the momentum are conserved,
over one cell the trace is exactly (sum m v^2 - P^2 / M) / A, 2 ekin less
the mean flow's, to 1e-9, and the stress isotropic within 2 % (grano
compare holds its hydrostatic column to the lattice's mean-field answer).

usage: stress_check.py GRANO WORKDIR
"""
import os
import subprocess
import sys

import h5py
import numpy as np

from tap import Tap

SCENE = """[scene]
name = stack
[domain]
width = 10
height = 20
gravity = 1
[material]
normal = linear
tangential = none
kn = 1e5
gamma_n = 440
[species]
diameter = 1
count = 100
[init]
kind = lattice
spacing = 1
velocity = zero
[measure]
field_cells = 1 20
[run]
until = 3
output_every = 1
stress = yes
"""

GAS = """[scene]
name = gas
seed = 3
[domain]
width = {L!r}
height = {L!r}
left = periodic
right = periodic
bottom = periodic
top = periodic
[material]
restitution = 1
[species]
diameter = 1
count = {n}
[init]
kind = random
velocity = gaussian
v0 = 1
[dsmc]
dt = 0.05
cell = 10
enskog = yes
[measure]
field_cells = 4 4
[run]
until = 60
output_every = 10
stress = yes
"""


def z_luding(eta):
    u = 1 - eta
    return 1 + 2 * eta * ((1 - 7 * eta / 16) / u ** 2 - eta ** 3 / (128 * u ** 4))


def z_henderson(eta):
    return (1 + eta * eta / 8) / (1 - eta) ** 2


TAP = Tap()
check = TAP.check


def run(grano, scene, method, out):
    """grano run quietly; the completed process."""
    return subprocess.run([grano, "run", scene, "--method", method, "--out", out, "--force", "-q"],
                          capture_output=True, text=True)


LATTICE = """[scene]
name = lattice-gas
seed = 3
[domain]
width = 55.42562584220407
height = 64
left = periodic
right = periodic
bottom = periodic
top = periodic
[species]
diameter = 1
count = 0
[init]
kind = occupation
occupation = 0.3
rest_occupation = 0.3
[lgca]
rules = granular
dt = 0.1
[measure]
field_cells = 1 1
[run]
until = 20
output_every = 2
stress = yes
"""


def lattice_gas(grano, work):
    """lgca's kinetic stress against its conserved energy and momentum."""
    scene = os.path.join(work, "lattice.ini")
    with open(scene, "w") as f:
        f.write(LATTICE)
    out = os.path.join(work, "lattice.h5")
    r = run(grano, scene, "lgca", out)
    if r.returncode:
        check(False, "lgca runs the lattice gas with [run] stress", r.stderr)
        return
    with h5py.File(out, "r") as f:
        g = f["fields/stress_global/value"][:].reshape(-1, 4)
        unit = f["fields/stress/value"].attrs["unit"]
        ek = f["observables/ekin_trans/value"][:]
        mom = f["observables/momentum/value"][:]
        mass = f["observables/mass/value"][:]
    area = 55.42562584220407 * 64
    check(np.all(np.isnan(g[0])), "lgca: the first frame's window is empty (NaN)")
    scale = np.sqrt(2 * ek[0] * mass[0])  # the momentum of all movers aligned
    conserved = np.ptp(ek) == 0 and np.ptp(mom, axis=0).max() < 1e-12 * scale
    check(conserved, "lgca: movers and momentum conserved (p = 0)")
    want = (2 * ek[0] - (mom[0, 0] ** 2 + mom[0, 1] ** 2) / mass[0]) / area
    tr = g[1:, 0] + g[1:, 3]
    err = np.max(np.abs(tr / want - 1))
    check(err < 1e-9, "lgca: trace = (sum m v^2 - P^2 / M) / A (max relative %.2g, tol 1e-9)" % err)
    an = np.max(np.abs(g[1:, 0] - g[1:, 3]) / tr + np.abs(g[1:, 1]) / tr)
    check(an < 0.02, "lgca: isotropic, |xx - yy| + |xy| under 2 %% of the trace (%.3g)" % an)
    check(unit in (b"m tau-2", "m tau-2"), "lgca: unit m tau-2", unit)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    grano, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    scene = os.path.join(work, "stack.ini")
    with open(scene, "w") as f:
        f.write(SCENE)
    for method, tol_cell, tol_vir in (("cd", 1e-9, 1e-9), ("dem", 1e-3, 1e-5)):
        out = os.path.join(work, method + ".h5")
        r = run(grano, scene, method, out)
        if r.returncode:
            check(False, "%s runs the stack" % method, r.stderr)
            continue
        with h5py.File(out, "r") as f:
            g = f["fields/stress_global/value"][-1].reshape(4)
            cells = f["fields/stress"]
            unit = cells["value"].attrs["unit"]
            s = cells["value"][-1]              # [ny][nx][4]
            y = f["particles/trajectory/position/value"][-1][:, 1]
            m = f["particles/trajectory/mass"][:]
        want = np.array([9.5 - k for k in range(10)] + [0.0] * 10)
        syy = s[:, 0, 3]
        err = np.max(np.abs(syy - want)) / 9.5
        check(err < tol_cell, "%s: cell sigma_yy = (9.5 - k) m g per row (max error %.2g of the base, tol %g)"
              % (method, err, tol_cell), syy)
        off = max(np.max(np.abs(s[:, 0, :3])), np.max(np.abs(g[:3]))) / 9.5
        check(off < 1e-9, "%s: sigma_xx, sigma_xy, sigma_yx vanish (%.2g)" % (method, off), s[:, 0, :3])
        vir = g[3] * 10 * 20 / np.sum(m * y) - 1
        check(abs(vir) < tol_vir, "%s: sigma_yy A = sum m g y (relative %.2g, tol %g)" % (method, vir, tol_vir))
        check(unit in (b"m tau-2", "m tau-2"), "%s: unit m tau-2" % method, unit)
    lattice_gas(grano, work)
    eta = 0.3
    for method, n, zref, ref in (("edmd", 600, z_luding(eta), "Luding"), ("dsmc", 3000, z_henderson(eta), "Henderson")):
        L = (n * np.pi / 4 / eta) ** 0.5
        gas = os.path.join(work, "gas-%s.ini" % method)
        with open(gas, "w") as f:
            f.write(GAS.format(L=L, n=n))
        out = os.path.join(work, "gas-%s.h5" % method)
        r = run(grano, gas, method, out)
        if r.returncode:
            check(False, "%s runs the gas" % method, r.stderr)
            continue
        with h5py.File(out, "r") as f:
            g = f["fields/stress_global/value"][:].reshape(-1, 4)
            unit = f["fields/stress/value"].attrs["unit"]
            cells = f["fields/stress/value"][:]          # [frames][ny][nx][4]
            v = f["particles/trajectory/velocity/value"][-1]
            m = f["particles/trajectory/mass"][:]
        check(np.all(np.isnan(g[0])) and np.all(np.isnan(cells[0])), "%s: the first frame's window is empty (NaN)" % method)
        nT = 0.5 * np.sum(m * (v[:, 0] ** 2 + v[:, 1] ** 2)) / (L * L)   # elastic: the energy stays
        P = 0.5 * (g[1:, 0] + g[1:, 3])
        z = np.mean(P) / nT
        check(abs(z / zref - 1) < 0.03, "%s: Z from the stress %.4f, %s %.4f (%+.2f %%, tol 3 %%)"
              % (method, z, ref, zref, 100 * (z / zref - 1)))
        xy = np.max(np.abs(g[1:, 1:3])) / np.mean(P)
        check(xy < 0.05, "%s: |sigma_xy| / P %.3g < 0.05" % (method, xy))
        mean = cells[1:].mean(axis=(1, 2))
        dev = np.max(np.abs(mean - g[1:])) / np.max(np.abs(g[1:]))
        check(dev < 1e-12, "%s: the domain's stress is the cells' mean (%.2g)" % (method, dev))
        check(unit in (b"m tau-2", "m tau-2"), "%s: unit m tau-2" % method, unit)
    return TAP.finish()


if __name__ == "__main__":
    sys.exit(main())
