#!/usr/bin/python3
"""Runs killed with SIGKILL at random moments (seeded), output and
checkpoint writes included: after every kill the result and the checkpoint
that exist must open with h5py, the run is continued from its checkpoint
into the same result, and the finished result must equal an uninterrupted
run's bit for bit (h5diff). TAP output, with the figures on a comment line.
Usage: fault_kill.py GRANO KILLS SEED"""
import os
import random
import signal
import subprocess
import sys
import tempfile
import time

import h5py

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
    unreadable, finished), last stderr."""
    kills = restarts = unreadable = 0
    for _ in range(40):
        argv = [GRANO, "run", scene, "-o", out, "-q"]
        argv += ["--restart", ckpt] if os.path.exists(ckpt) else ["--force"]
        restarts += "--restart" in argv
        p = subprocess.Popen(argv, stderr=subprocess.PIPE, text=True)
        try:
            err = p.communicate(timeout=rng.uniform(0.0, 0.5 * wall))[1]
            return (kills, restarts, unreadable, p.returncode == 0), err
        except subprocess.TimeoutExpired:
            p.send_signal(signal.SIGKILL)
            p.communicate()
            kills += 1
            bad = [x for x in (out, ckpt) if not readable(x)]
            unreadable += len(bad)
            results.append(("kill: files readable", not bad, ", ".join(bad)))
    return (kills, restarts, unreadable, False), "40 kills without finishing"


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
            for x in (out, ckpt):
                if os.path.exists(x):
                    os.unlink(x)
            ok, err = run_round(rng, scene, out, ckpt, wall, results)
            kills += ok[0]
            restarts += ok[1]
            unreadable += ok[2]
            if not ok[3]:
                results.append(("round %d finishes" % rounds, False, err))
                break
            same = subprocess.run(["h5diff", ref, out], capture_output=True, text=True)
            identical += same.returncode == 0
            results.append(("round %d: %d kills, %d restarts, identical to the uninterrupted run" % (rounds, ok[0], ok[1]),
                            same.returncode == 0, same.stdout[-2000:]))
    for i, (name, good, why) in enumerate(results, 1):
        print("%s %d - %s" % ("ok" if good else "not ok", i, name))
        if not good and why:
            print("# " + why.replace("\n", "\n# "))
    print("# figures: kills %d, unreadable files after a kill %d, restarts %d, rounds %d, bit-identical %d"
          % (kills, unreadable, restarts, rounds, identical))
    print("1..%d" % len(results))
    return 0 if all(r[1] for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
