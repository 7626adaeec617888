#!/usr/bin/python3
"""The flow fluctuations of a silo-flow result against the block length
and the filling protocol (docs/experiments.md, "Fluctuations, density law
and the filling protocol").

usage: silo_blocks.py RESULT.h5 [RESULT.h5 ...]

For each file: the bulk packing of every realisation's settled silo (mean,
spread), the flow rate per orifice, and the reduced-flow fluctuations
pooled over D <= 9 and D > 9 with blocks merged 1, 2, 4, 8 at a time:
number of blocks, kurtosis, KS distance to eq. 4.4 and to the Gaussian.
"""
import sys

import h5py
import numpy as np


def cdf_eq44(u):
    # P(u) = (2/pi) / (1 + u^2)^2, unit variance
    return 0.5 + (np.arctan(u) + u / (1 + u * u)) / np.pi


def cdf_gauss(u):
    from math import erf, sqrt
    return np.array([0.5 * (1 + erf(v / sqrt(2))) for v in u])


def ks(u, cdf):
    u = np.sort(u)
    n = len(u)
    f = cdf(u)
    return max(np.max(np.arange(1, n + 1) / n - f), np.max(f - np.arange(n) / n))


def table(f, name):
    """A table of the file, its columns by name."""
    return {k: (v.asstr()[()] if v.dtype.kind == "O" else v[()]) for k, v in f[name].items()}


def main(paths):
    for path in paths:
        f = h5py.File(path, "r")
        cfg = table(f, "config")
        block_tau = cfg["block_time"][0]
        flow, real, blocks = table(f, "flow"), table(f, "realisations"), table(f, "blocks")
        Ds = flow["D"]
        nreal = int(cfg["realisations"][0])
        # bulk packing of each realisation's settled silo (its branches to
        # every orifice averaged: they differ only in the bottom layer)
        bulk = np.array([[real["bulk_packing"][(real["D"] == D) & (real["realisation"] == q)][0] for D in Ds]
                         for q in range(nreal)])
        per_real = bulk.mean(axis=1)
        print("%s: bulk packing per realisation %s, mean %.4f, sd %.4f; sd over the branches of one realisation %.4f" % (
            path, " ".join("%.4f" % v for v in per_real), per_real.mean(),
            per_real.std(ddof=1) if nreal > 1 else 0, bulk.std(axis=1, ddof=1).mean() if len(Ds) > 1 else 0))

        def counts(D, q):
            return blocks["grains"][(blocks["D"] == D) & (blocks["realisation"] == q)].astype(float)

        for D in Ds:
            w = [counts(D, q).mean() / block_tau for q in range(nreal)]
            print("  D %g: W per realisation %s" % (D, " ".join("%.2f" % v for v in w)))
        print("  D W W_err packing: " + "; ".join("%g %.2f %.2f %.3f" % (flow["D"][i], flow["W"][i], flow["W_err"][i],
                                                                         flow["packing"][i]) for i in range(len(Ds))))
        for merge in (1, 2, 4, 8):
            for side, sel in (("D<=9", Ds <= 9), ("D>9", Ds > 9)):
                pool = []
                for D in Ds[sel]:
                    for q in range(nreal):
                        c = counts(D, q)
                        nb = len(c) // merge * merge
                        c = c[:nb].reshape(-1, merge).sum(axis=1)
                        w = c / c.mean() if c.mean() > 0 else None
                        if w is None:
                            continue
                        s = np.sqrt(np.mean(w * w) - 1)
                        if s > 0:
                            pool.extend((w - 1) / s)
                pool = np.array(pool)
                if len(pool) < 8:
                    continue
                kap = np.mean(pool ** 4) / 3 - 1
                print("  blocks of %.3g tau, %s: n %d, kappa %.2f, KS eq4.4 %.3f, KS gauss %.3f" % (
                    merge * block_tau, side, len(pool), kap, ks(pool, cdf_eq44), ks(pool, cdf_gauss)))


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
