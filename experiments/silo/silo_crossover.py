#!/usr/bin/python3
"""Where the start of a discharge stops being ballistic, from `grano
silo-start` outputs: python3 experiments/silo/silo_crossover.py DIR [DIR ...]

Per orifice of each DIR: the MSD exponents the report fitted (summary.dat:
a fall of 0.01 d to 1 d, or the longest lag), the local slope
d ln<dx^2> / d ln t (msd_D<D>.dat, between neighbouring lags) at a fall of
0.1 d and 1 d, and the crossover: the mean fall at which the local slope
first drops below 1.8, in x and y (interpolated in ln fall; '>' the longest
lag's fall where it never does). One line per orifice, for a sensitivity
table across runs that differ in one choice."""
import glob
import sys

import numpy as np

CROSS = 1.8


def local_slopes(path):
    a = np.loadtxt(path)
    a = a[np.isfinite(a[:, 3]) & (a[:, 2] > 0)]  # lags no discharge reached
    lag, fall, mx, my = a[:, 0], a[:, 3], a[:, 4], a[:, 5]
    mid = np.sqrt(fall[1:] * fall[:-1])
    dl = np.diff(np.log(lag))
    return mid, np.diff(np.log(mx)) / dl, np.diff(np.log(my)) / dl


def crossing(fall, slope):
    below = np.nonzero(slope < CROSS)[0]
    if not len(below):
        return ">%.3g" % fall[-1]
    k = below[0]
    if k == 0:
        return "<%.3g" % fall[0]
    f = (CROSS - slope[k - 1]) / (slope[k] - slope[k - 1])
    return "%.3g" % np.exp(np.log(fall[k - 1]) + f * (np.log(fall[k]) - np.log(fall[k - 1])))


def at(fall, slope, f):
    return np.interp(np.log(f), np.log(fall), slope) if fall[0] <= f <= fall[-1] else np.nan


def summary(d):
    rows = {}
    with open(d + "/summary.dat") as f:
        cols = f.readline().lstrip("# ").split()
        for line in f:
            v = dict(zip(cols, map(float, line.split())))
            rows["%g" % v["D"]] = v
    return rows


print("# dir D n exp_x exp_y slope_x,y@0.1d slope_x,y@1d crossover_fall_x crossover_fall_y (d)")
for d in sys.argv[1:]:
    s = summary(d)
    for path in sorted(glob.glob(d + "/msd_D*.dat"), key=lambda p: float(p.split("_D")[-1][:-4])):
        D = path.split("_D")[-1][:-4]
        fall, sx, sy = local_slopes(path)
        v = s.get(D, {})
        print("%s %s %d %.3f±%.3f %.3f±%.3f %.2f,%.2f %.2f,%.2f %s %s" % (
            d, D, v.get("realisations", 0), v.get("exp_x", np.nan), v.get("exp_x_err", np.nan),
            v.get("exp_y", np.nan), v.get("exp_y_err", np.nan), at(fall, sx, 0.1), at(fall, sy, 0.1),
            at(fall, sx, 1.0), at(fall, sy, 1.0), crossing(fall, sx), crossing(fall, sy)))
