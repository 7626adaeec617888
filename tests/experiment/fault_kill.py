#!/usr/bin/python3
"""Runs killed with SIGKILL at random moments (seeded), output and
checkpoint writes included, against what docs/reliability.md promises:
after every kill the checkpoint that exists opens with h5py; the result
opens too, but for a kill in the middle of HDF5's metadata flush (about
0.2 % of kills), after which the run goes on from the checkpoint into a new
file (--restart CKPT --out NEW); at most max(1, 5 % of the kills) results
are lost so. The run is continued until it finishes, and the finished
result must equal an uninterrupted run's: bit for bit (h5diff) when it
stayed in one file, else the new file's frames those of the uninterrupted
run's last ones. TAP output, with the figures on a comment line.
Usage: fault_kill.py GRANO KILLS SEED"""
import glob
import os
import random
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy

GRANO, KILLS, SEED = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])

# Checkpoints and frames often, so kills land in both kinds of write.
SCENE = """[domain]
width = 30
height = 30
gravity = 1
[material]
tangential = spring
kn = 1e5
gamma_n = 100
mu = 0.5
[species]
count = 300
polydispersity = 0.1
[init]
kind = random
velocity = gaussian
v0 = 1
[run]
until = 1.5
output_every = 0.01
checkpoint_every = 0.05
"""


def readable(path):
    if not os.path.exists(path):
        return True
    try:
        with h5py.File(path, "r") as f:
            f.visit(lambda name: None)
        return True
    except Exception:
        return False


def run_round(rng, scene, out, ckpt, wall, results):
    """Kill at random moments until the run finishes; (kills, restarts,
    unreadable results, finished, the file the run ended in), last stderr."""
    kills = restarts = unreadable = 0
    cur, cur_ckpt = out, ckpt
    for _ in range(40):
        # a run into a new file writes its own checkpoint beside it
        if cur != out and os.path.exists(os.path.splitext(cur)[0] + ".ckpt"):
            cur_ckpt = os.path.splitext(cur)[0] + ".ckpt"
        argv = [GRANO, "run", scene, "-o", cur, "-q"]
        argv += ["--restart", cur_ckpt] if os.path.exists(cur_ckpt) else ["--force"]
        restarts += "--restart" in argv
        p = subprocess.Popen(argv, stderr=subprocess.PIPE, text=True)
        try:
            err = p.communicate(timeout=rng.uniform(0.0, 0.5 * wall))[1]
            return (kills, restarts, unreadable, p.returncode == 0, cur), err
        except subprocess.TimeoutExpired:
            p.send_signal(signal.SIGKILL)
            p.communicate()
            kills += 1
            results.append(("kill %d: checkpoint readable" % kills, readable(cur_ckpt), cur_ckpt))
            if not readable(cur):
                # what reliability.md says to do: go on from the checkpoint in a new file
                unreadable += 1
                cur = "%s-after-kill-%d.h5" % (os.path.splitext(out)[0], kills)
                how = "from the checkpoint" if os.path.exists(cur_ckpt) else "from the start (no checkpoint yet)"
                results.append(("kill %d: result unreadable, continued %s into %s"
                                % (kills, how, os.path.basename(cur)), None, ""))
    return (kills, restarts, unreadable, False, cur), "40 kills without finishing"


def tail_equal(ref, part):
    """Every dataset of part equals ref's (its last rows where part holds
    fewer frames); '' or what differs."""
    bad = []
    with h5py.File(ref, "r") as r, h5py.File(part, "r") as q:
        def check(name, obj):
            if not isinstance(obj, h5py.Dataset):
                return
            if name not in r:
                bad.append(name + ": not in the uninterrupted run's result")
                return
            a, b = numpy.asarray(r[name][()]), numpy.asarray(obj[()])
            if a.shape != b.shape:
                if a.ndim == 0 or a.shape[1:] != b.shape[1:] or b.shape[0] > a.shape[0] or b.shape[0] == 0:
                    bad.append("%s: shape %s against %s" % (name, b.shape, a.shape))
                    return
                a = a[a.shape[0] - b.shape[0]:]
            nan = a.dtype.kind in "fc" and b.dtype.kind in "fc"  # an observable may be NaN by definition
            if not numpy.array_equal(a, b, equal_nan=nan):
                bad.append(name + ": values differ")
            seen.append(name)
        seen = []
        q.visititems(check)
        if not any("position" in x for x in seen):
            bad.append("no positions in " + part)
    return "; ".join(bad)


def main():
    rng = random.Random(SEED)
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        scene = os.path.join(tmp, "k.ini")
        with open(scene, "w") as f:
            f.write(SCENE)
        ref = os.path.join(tmp, "ref.h5")
        t0 = time.monotonic()
        subprocess.run([GRANO, "run", scene, "-o", ref, "-q"], check=True)
        wall = time.monotonic() - t0
        out, ckpt = os.path.join(tmp, "k.h5"), os.path.join(tmp, "k.ckpt")
        kills = restarts = unreadable = rounds = identical = 0
        # Rounds from a fresh start until enough kills: each round is killed
        # until it finishes, then compared with the reference.
        while kills < KILLS and rounds < KILLS:
            rounds += 1
            for x in [out, ckpt] + glob.glob(os.path.splitext(out)[0] + "-after-kill-*"):
                if os.path.exists(x):
                    os.unlink(x)
            ok, err = run_round(rng, scene, out, ckpt, wall, results)
            kills += ok[0]
            restarts += ok[1]
            unreadable += ok[2]
            if not ok[3]:
                results.append(("round %d finishes" % rounds, False, err))
                break
            if ok[4] == out:
                same = subprocess.run(["h5diff", ref, out], capture_output=True, text=True)
                good, why = same.returncode == 0, same.stdout[-2000:]
                what = "identical to the uninterrupted run"
            else:
                why = tail_equal(ref, ok[4])
                good, what = not why, "its new file's frames those of the uninterrupted run"
            identical += good
            results.append(("round %d: %d kills, %d restarts, %s" % (rounds, ok[0], ok[1], what), good, why))
        results.append(("results lost to a kill: %d of %d kills, at most max(1, 5 %%)" % (unreadable, kills),
                        unreadable <= max(1, kills // 20), ""))
    tests = 0
    for name, good, why in results:
        if good is None:  # what happened, not a test
            print("# " + name)
            continue
        tests += 1
        print("%s %d - %s" % ("ok" if good else "not ok", tests, name))
        if not good and why:
            print("# " + why.replace("\n", "\n# "))
    print("# figures: kills %d, results unreadable after a kill %d, restarts %d, rounds %d, "
          "equal to the uninterrupted run %d" % (kills, unreadable, restarts, rounds, identical))
    print("1..%d" % tests)
    return 0 if all(r[1] is not False for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
