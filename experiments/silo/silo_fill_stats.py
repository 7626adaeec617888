#!/usr/bin/python3
"""Fillings and discharges of `grano silo-start` runs, from their parts:
python3 experiments/silo/silo_fill_stats.py DIR [DIR ...]

Per run: the filling's settling time and CPU seconds, the settled surface
(mean height of the 50 highest grains), the packing fraction of the settled
silo over silo-flow's bulk region (5 d from the walls, 16 d above the base
to 10 d below the highest grain) and over 20-80 d above the base; per
orifice: the branch and the discharge (CPU s, steps), the grains out and
the flow rate over the discharge. Means with their spread (sd) over the
realisations. Thesis-size silo (50 d wide, base at 5 d) assumed."""
import glob
import re
import sys

import h5py
import numpy as np

W, BASE, X0, DT = 50.0, 5.0, 1.0, 1.25e-4


def packing(x, y, r, x0, y0, x1, y1, h=0.02):
    """Area fraction of the disks in the rectangle (grid quadrature at the edges)."""
    inside = (x - r >= x0) & (x + r <= x1) & (y - r >= y0) & (y + r <= y1)
    a = np.sum(np.pi * r[inside] ** 2)
    cross = ~inside & (x + r > x0) & (x - r < x1) & (y + r > y0) & (y - r < y1)
    for xi, yi, ri in zip(x[cross], y[cross], r[cross]):
        gx = np.arange(max(x0, xi - ri) + h / 2, min(x1, xi + ri), h)
        gy = np.arange(max(y0, yi - ri) + h / 2, min(y1, yi + ri), h)
        gxx, gyy = np.meshgrid(gx, gy)
        a += np.sum((gxx - xi) ** 2 + (gyy - yi) ** 2 < ri * ri) * h * h
    return a / ((x1 - x0) * (y1 - y0))


def fill_row(path):
    c = h5py.File(path, "r")["checkpoint"]
    v = c["settled"][:].reshape(-1, 6)
    m = (v[:, 5].astype(int) & 1) == 0
    x, y, r = v[m, 0], v[m, 1], v[m, 4]
    return [float(np.ravel(c["t_settle"][()])[0]), c["cost"][1], np.sort(y)[-50:].mean(),
            packing(x, y, r, X0 + 5, BASE + 16, X0 + W - 5, y.max() - 10),
            packing(x, y, r, X0 + 5, BASE + 20, X0 + W - 5, BASE + 80)]


def show(name, cols, rows):
    a = np.array(rows)
    sd = a.std(axis=0, ddof=1) if len(a) > 1 else np.zeros(a.shape[1])
    print("  %s (%d): " % (name, len(a)) + ", ".join("%s %.4g (sd %.2g)" % (k, m, s) for k, m, s in zip(cols, a.mean(0), sd)))


for d in sys.argv[1:]:
    print(d)
    fills = [fill_row(p) for p in sorted(glob.glob(d + "/parts/fill-r*.part"))]
    if fills:
        show("fillings", ["t_settle", "CPU s", "surface", "phi bulk", "phi 20-80"], fills)
    by_d = {}
    for p in sorted(glob.glob(d + "/parts/start-D*-r*.part")):
        c = h5py.File(p, "r")["checkpoint"]
        cost, br, ts = c["cost"][:], c["branch"][:], c["series"][:].reshape(-1, 3)
        by_d.setdefault(re.search(r"start-D([0-9.]+)-r", p).group(1), []).append(
            [br[0], br[1], cost[1], cost[4], cost[3], ts[-1, 2], ts[-1, 2] / (cost[4] * DT)])
    for D, rows in sorted(by_d.items(), key=lambda kv: float(kv[0])):
        show("D %s" % D, ["branch tau", "lift", "branch CPU s", "steps", "run CPU s", "out", "W"], rows)
