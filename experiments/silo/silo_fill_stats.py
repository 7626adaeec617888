#!/usr/bin/python3
"""Fillings and discharges of `grano silo-start` runs, from their parts:
python3 experiments/silo/silo_fill_stats.py DIR [DIR ...]

Per run: the filling's settling time and CPU seconds, the settled surface
(mean height of the 50 highest grains), the packing fraction of the settled
silo over silo-flow's bulk region (5 d from the walls, 16 d above the base
to 10 d below the highest grain) and over 20-80 d above the base, its
profile in 10 d bands above the base, and the contact number (contacts per
grain, walls included, of the grains 5 d from the walls between 10 d above
the base and 10 d below the surface); where the filling's time went (its
trace: the time and CPU seconds until the first grain, half of them and 99 %
are in the container, and then until it settled); per orifice: the branch
and the discharge (CPU s, steps), the grains out and the flow rate over the
discharge. Means with their spread (sd) over the realisations; with two
or more DIRs, each filling figure of the others against the first's, in
standard errors of the difference. Thesis-size silo (50 d wide, base at 5 d)
assumed."""
import glob
import re
import sys

import h5py
import numpy as np
from scipy.spatial import cKDTree

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


BANDS = [(BASE + 10 * k, BASE + 10 * (k + 1)) for k in range(9)]
FILL_COLS = (["t_settle", "CPU s", "surface", "phi bulk", "phi 20-80", "Z"]
             + ["phi %d-%d" % (a - BASE, b - BASE) for a, b in BANDS]
             + ["t first", "t half", "t 99%", "t tail", "CPU first", "CPU half", "CPU 99%", "CPU tail"])


def contact_number(v, m, surface):
    """Contacts per grain (overlapping pairs, walls included) of the bulk grains."""
    pairs = cKDTree(v[:, :2]).query_pairs(1.0 - 1e-12, output_type="ndarray")
    i, j = pairs[:, 0], pairs[:, 1]
    touch = np.hypot(*(v[i, :2] - v[j, :2]).T) < v[i, 4] + v[j, 4]
    z = np.bincount(np.concatenate([i[touch], j[touch]]), minlength=len(v))
    x, y = v[:, 0], v[:, 1]
    bulk = m & (x > X0 + 5) & (x < X0 + W - 5) & (y > BASE + 10) & (y < surface - 10)
    return z[bulk].mean()


def trace_times(c):
    """(time, CPU s) when 1 grain, half and 99 % are inside, and from 99 % to settled."""
    if "trace" not in c:
        return [np.nan] * 8
    tr = c["trace"][:].reshape(-1, 4)
    n = tr[-1, 2]
    rows = [np.argmax(tr[:, 2] >= k) for k in (1, n / 2, 0.99 * n)]
    t = [tr[k, 0] for k in rows] + [tr[-1, 0] - tr[rows[2], 0]]
    cpu = [tr[k, 1] for k in rows] + [tr[-1, 1] - tr[rows[2], 1]]
    return t + cpu


def fill_row(path):
    c = h5py.File(path, "r")["checkpoint"]
    v = c["settled"][:].reshape(-1, 6)
    m = (v[:, 5].astype(int) & 1) == 0
    x, y, r = v[m, 0], v[m, 1], v[m, 4]
    surface = np.sort(y)[-50:].mean()
    return ([float(np.ravel(c["t_settle"][()])[0]), c["cost"][1], surface,
             packing(x, y, r, X0 + 5, BASE + 16, X0 + W - 5, y.max() - 10),
             packing(x, y, r, X0 + 5, BASE + 20, X0 + W - 5, BASE + 80), contact_number(v, m, surface)]
            + [packing(x, y, r, X0 + 5, a, X0 + W - 5, b) for a, b in BANDS] + trace_times(c))


def show(name, cols, rows):
    a = np.array(rows)
    sd = a.std(axis=0, ddof=1) if len(a) > 1 else np.zeros(a.shape[1])
    print("  %s (%d): " % (name, len(a)) + ", ".join("%s %.4g (sd %.2g)" % (k, m, s) for k, m, s in zip(cols, a.mean(0), sd)))


def against(name, first, other):
    """Each figure of `other` against `first`: difference in standard errors."""
    a, b = np.array(first), np.array(other)
    se = np.sqrt(a.var(0, ddof=1) / len(a) + b.var(0, ddof=1) / len(b))
    print("  %s against the first: " % name + ", ".join(
        "%s %+.3g (%+.1f se)" % (k, db, db / s if s > 0 else np.nan)
        for k, db, s in zip(FILL_COLS, b.mean(0) - a.mean(0), se)))


first = None
for d in sys.argv[1:]:
    print(d)
    fills = [fill_row(p) for p in sorted(glob.glob(d + "/parts/fill-r*.part"))]
    if fills:
        show("fillings", FILL_COLS, fills)
        if first is None:
            first = fills
        elif len(first) > 1 and len(fills) > 1:
            against("fillings", first, fills)
    by_d = {}
    for p in sorted(glob.glob(d + "/parts/start-D*-r*.part")):
        c = h5py.File(p, "r")["checkpoint"]
        cost, br, ts = c["cost"][:], c["branch"][:], c["series"][:].reshape(-1, 3)
        by_d.setdefault(re.search(r"start-D([0-9.]+)-r", p).group(1), []).append(
            [br[0], br[1], cost[1], cost[4], cost[3], ts[-1, 2], ts[-1, 2] / (cost[4] * DT)])
    for D, rows in sorted(by_d.items(), key=lambda kv: float(kv[0])):
        show("D %s" % D, ["branch tau", "lift", "branch CPU s", "steps", "run CPU s", "out", "W"], rows)
