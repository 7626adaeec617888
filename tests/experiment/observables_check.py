#!/usr/bin/env python3
"""What a run writes under observables/ is what its method declares, and a
broken validity limit reaches the user.

- lgca on the pipe scene: mass, momentum, moving and resting populations,
  no NaN anywhere, no particle quantity the lattice does not model; the mass
  equals m (moving + resting) in every sample and is conserved (the pipe
  reinserts what leaves, FHP collisions conserve particles).
- dsmc with cells of 4 d on compare's dilute gas (1024 grains, n = 0.127)
  and ppc_min = 4: some 2.1 particles per cell < 4, so stderr names the
  limit, the value measured and the key ppc_min, the file counts every step
  in limit_ppc_min (with its key as an attribute), and [run] strict = yes
  stops the run with exit 1, its checkpoint holding the state before the
  first step (t = 0).
- dsmc on a gas dilute enough for every limit (cells of 100 d, lambda = 278 d,
  16 per cell): no warning, every limit counter 0.

usage: observables_check.py GRANO SOURCE_ROOT WORKDIR
"""
import os
import re
import subprocess
import sys

import h5py
import numpy as np

from tap import Tap


def run(grano, scene, method, out, *sets):
    args = [grano, "run", scene, "--method", method, "--out", out, "--force", "-q"]
    for s in sets:
        args += ["--set", s]
    return subprocess.run(args, capture_output=True, text=True)


def values(path):
    with h5py.File(path) as f:
        return {k: v["value"][()] for k, v in f["observables"].items()}, \
               {k: dict(v["value"].attrs) for k, v in f["observables"].items()}


def lattice(t, grano, root, work):
    out = os.path.join(work, "pipe.h5")
    r = run(grano, os.path.join(root, "experiments/scenes/lgca-pipe.ini"), "lgca", out,
            "run.until=200", "run.observe_every=20")
    t.check(r.returncode == 0, "lgca pipe runs", r.stderr)
    if r.returncode:
        return
    v, _ = values(out)
    want = {"mass", "momentum", "moving", "resting", "ekin_trans", "epot_grav", "temperature", "steps", "outflow",
            "reinserted", "lost"}
    t.check(set(v) == want, "lgca writes exactly its declared observables", sorted(set(v) ^ want))
    nan = [k for k, a in v.items() if a.dtype.kind == "f" and not np.all(np.isfinite(a))]
    t.check(not nan, "no lgca observable is NaN", nan)
    total = v["moving"] + v["resting"]
    t.check(len(total) >= 10 and np.array_equal(v["mass"], total.astype(float)),
            "mass = m (moving + resting) in every sample (m = 1)", (v["mass"], total))
    t.check(np.all(total == total[0]), "the pipe conserves the particles", total)


def dsmc_limits(t, grano, root, work):
    scene = os.path.join(root, "experiments/scenes/compare/cooling-dilute.ini")
    out = os.path.join(work, "dilute.h5")
    small = ("dsmc.enskog=no", "dsmc.cell=4", "dsmc.ppc_min=4")
    r = run(grano, scene, "dsmc", out, "run.until=0.5", *small)
    t.check(r.returncode == 0, "dsmc with cells of 4 d runs (exit 0)", r.stderr)
    first = [l for l in r.stderr.splitlines() if "limit_ppc_min broken at" in l]
    m = re.search(r"is ([0-9.]+), below ppc_min = 4", first[0]) if len(first) == 1 else None
    t.check(m is not None and 1.8 < float(m.group(1)) < 2.4 and "key 'ppc_min'" in first[0],
            "stderr says once: limit, value measured, the key that changes it", r.stderr)
    t.check(any("limit_ppc_min counted 50 in 50 steps of the run" in l for l in r.stderr.splitlines()),
            "the run's summary counts the steps that broke it", r.stderr)
    if r.returncode == 0:
        v, attrs = values(out)
        key = attrs["limit_ppc_min"].get("validity_key", b"")
        t.check(v["limit_ppc_min"][-1] == 50 and key in (b"dsmc.ppc_min", "dsmc.ppc_min"),
                "the file counts it, with its key", (v["limit_ppc_min"], key))
        info = subprocess.run([grano, "info", out], capture_output=True, text=True)
        t.check("limit_ppc_min      50  <- validity limit broken" in info.stdout, "grano info marks it", info.stdout)
    out = os.path.join(work, "strict.h5")
    r = run(grano, scene, "dsmc", out, "run.until=0.5", *small, "run.strict=yes")
    t.check(r.returncode == 1 and "limit_ppc_min" in r.stderr and "stopped" in r.stderr,
            "[run] strict = yes stops the run, exit 1", (r.returncode, r.stderr))
    ck = os.path.join(work, "strict.ckpt")
    if os.path.exists(ck):
        with h5py.File(ck) as f:
            steps = f["checkpoint/run_counters"][()] if "checkpoint/run_counters" in f else None
        info = subprocess.run([grano, "info", ck], capture_output=True, text=True)
        t.check("t = 0 .. 0" in info.stdout, "the checkpoint keeps the state before the step (t = 0)",
                (steps, info.stdout))
    else:
        t.check(False, "the strict run left its checkpoint", ck)


def dsmc_valid(t, grano, root, work):
    scene = os.path.join(root, "experiments/scenes/compare/cooling-dilute.ini")
    out = os.path.join(work, "valid.h5")
    r = run(grano, scene, "dsmc", out, "run.until=2", "domain.width=897", "domain.height=897",
            "dsmc.cell=100", "dsmc.enskog=no", "run.strict=yes")
    t.check(r.returncode == 0 and "validity" not in r.stderr, "a dsmc gas within every limit: no warning",
            r.stderr)
    if r.returncode == 0:
        v, _ = values(out)
        lim = {k: int(a[-1]) for k, a in v.items() if k.startswith("limit_")}
        t.check(len(lim) == 5 and not any(lim.values()), "every limit counter 0", lim)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    grano, root, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    t = Tap()
    lattice(t, grano, root, work)
    dsmc_limits(t, grano, root, work)
    dsmc_valid(t, grano, root, work)
    return t.finish()


if __name__ == "__main__":
    sys.exit(main())
