#!/usr/bin/env python3
"""Corruption is detected: a byte flipped in a copy of a result (in a
trajectory, an observable, a field) or of a checkpoint makes `grano info
--verify` exit 1 naming the damaged dataset, and `grano run --restart`
refuse the damaged checkpoint naming its array; never a crash (exit
status above 2, a signal) nor a silent restart. The undamaged files verify.
TAP.

usage: verify_check.py GRANO SOURCE_ROOT WORKDIR
"""
import os
import shutil
import subprocess
import sys

import h5py

GRANO, ROOT, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
SCENE = os.path.join(ROOT, "experiments", "scenes", "box.ini")
results = []


def grano(*args):
    r = subprocess.run([GRANO] + list(args), capture_output=True, text=True, timeout=300)
    return r.returncode, r.stdout, r.stderr


def flip(src, dst, dset):
    """A copy of src with one byte flipped in the middle of dset's first
    chunk (its offset from HDF5's chunk index)."""
    shutil.copyfile(src, dst)
    with h5py.File(src, "r") as f:
        info = f[dset].id.get_chunk_info(0)
    off = info.byte_offset + info.size // 2
    with open(dst, "r+b") as g:
        g.seek(off)
        b = g.read(1)
        g.seek(off)
        g.write(bytes([b[0] ^ 0x5A]))


def check(name, ok, detail=""):
    results.append((ok, name, detail))


os.makedirs(WORK, exist_ok=True)
res, ckpt = os.path.join(WORK, "r.h5"), os.path.join(WORK, "r.ckpt")
rc, out, err = grano("run", SCENE, "--until", "2", "--out", res, "--force", "-q",
                     "--set", "measure.field_cells=6 6")
check("the run writes its result and checkpoint", rc == 0, err)
for path in (res, ckpt):
    rc, out, err = grano("info", "--verify", path)
    check("%s verifies: no checksum failed" % os.path.basename(path),
          rc == 0 and "no checksum failed" in out, out + err)

with h5py.File(res, "r") as f:
    fields = sorted(k for k in f.get("fields", {}).keys())
targets = [(res, "particles/trajectory/position/value"), (res, "observables/ekin_trans/value")]
if fields:
    targets.append((res, "fields/%s/value" % fields[0]))
targets.append((ckpt, "checkpoint/dem_x"))
for src, dset in targets:
    bad = os.path.join(WORK, "bad-" + dset.replace("/", "_") + os.path.splitext(src)[1])
    flip(src, bad, dset)
    rc, out, err = grano("info", "--verify", bad)
    check("a flipped byte in %s: --verify exits 1 naming it" % dset,
          rc == 1 and ("/" + dset) in err, "exit %d: %s" % (rc, (out + err)[-400:]))
    if src == ckpt:
        rc, out, err = grano("run", SCENE, "--until", "3", "--out", os.path.join(WORK, "r2.h5"), "--force",
                             "--restart", bad, "-q", "--set", "measure.field_cells=6 6")
        check("--restart refuses the damaged checkpoint naming dem_x (no crash, no run)",
              rc in (1, 2) and "dem_x" in err and not os.path.exists(os.path.join(WORK, "r2.h5")),
              "exit %d: %s" % (rc, err[-400:]))

print("1..%d" % len(results))
for i, (ok, name, detail) in enumerate(results, 1):
    print("%s %d - %s" % ("ok" if ok else "not ok", i, name))
    if not ok:
        for line in detail.strip().splitlines()[-8:]:
            print("# " + line)
sys.exit(0 if all(r[0] for r in results) else 1)
