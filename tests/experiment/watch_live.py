#!/usr/bin/python3
"""A result read while its run writes it (docs/reliability.md): grano info
and h5py in SWMR read mode (a fresh open each time, and one open file
whose dataset is refreshed) see the frames grow, each frame they read
equal to the same frame of the finished file; grano info says the file is
being written. Then a killed run's file reads the same way. TAP.
Usage: watch_live.py GRANO"""
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy

GRANO = sys.argv[1]
SCENE = """[domain]
width = 40
height = 40
gravity = 1
[species]
count = 600
[init]
kind = random
velocity = gaussian
v0 = 1
[run]
until = 8
output_every = 0.05
"""
POS = "particles/trajectory/position/value"
results = []


def check(name, good, why=""):
    results.append((name, bool(good), why))


def info_frames(path):
    out = subprocess.run([GRANO, "info", path], capture_output=True, text=True)
    m = re.search(r"^frames\s+(\d+)", out.stdout, re.M)
    return (int(m.group(1)) if m else -1), out.stdout, out.returncode


def watch(path, proc):
    """Poll until the run ends: counts from grano info, fresh h5py opens and
    one refreshed dataset, with a frame read each time."""
    counts = {"info": [], "open": [], "refresh": []}
    seen, said, held = {}, False, None
    while proc.poll() is None:
        time.sleep(0.2)
        if not os.path.exists(path):
            continue
        n, text, rc = info_frames(path)
        if rc == 0 and n >= 0:
            counts["info"].append(n)
            said = said or "writing      a run is writing it" in text
        try:
            with h5py.File(path, "r", swmr=True) as f:
                d = f[POS]
                counts["open"].append(d.shape[0])
                if d.shape[0]:
                    seen[d.shape[0] - 1] = d[d.shape[0] - 1]
            if held is None:
                held = h5py.File(path, "r", swmr=True)
            d = held[POS]
            d.refresh()
            counts["refresh"].append(d.shape[0])
        except (OSError, KeyError) as e:
            check("h5py opens the running file in SWMR read mode", False, str(e))
            break
    if held is not None:
        held.close()
    return counts, seen, said


def grows(xs):
    return len(set(xs)) >= 3 and all(b >= a for a, b in zip(xs, xs[1:]))


def main():
    with tempfile.TemporaryDirectory() as tmp:
        scene, out = os.path.join(tmp, "w.ini"), os.path.join(tmp, "w.h5")
        with open(scene, "w") as f:
            f.write(SCENE)
        p = subprocess.Popen([GRANO, "run", scene, "-o", out, "-q"], stderr=subprocess.PIPE)
        counts, seen, said = watch(out, p)
        err = p.communicate()[1].decode()
        check("the run finishes", p.returncode == 0, err)
        for how, xs in counts.items():
            check("frames seen growing while it runs (%s): %s" % (how, xs[:3] + ["..."] + xs[-2:]),
                  grows(xs), str(xs))
        check("grano info says the file is being written", said)
        with h5py.File(out, "r") as f:
            d = f[POS]
            same = all(numpy.array_equal(d[k], v) for k, v in seen.items())
            check("%d frames read while it ran equal the finished file's" % len(seen), seen and same)
        n, text, _ = info_frames(out)
        check("the finished file is not 'being written'", "writing " not in text, text)

        # killed: the same reads, the same frames (a run ten times longer,
        # which no machine finishes before the kill)
        p = subprocess.Popen([GRANO, "run", scene, "-o", out, "-q", "--force", "--until", "80"])
        time.sleep(1.0)
        while p.poll() is None and info_frames(out)[0] < 5:
            time.sleep(0.1)
        p.send_signal(signal.SIGKILL)
        p.wait()
        n, text, rc = info_frames(out)
        with h5py.File(out, "r", swmr=True) as f:
            m = f[POS].shape[0]
        check("a killed run's file: grano info and h5py read its %d frames" % m,
              rc == 0 and n == m >= 5 and "killed" in text, text)
    print("1..%d" % len(results))
    for k, (name, good, why) in enumerate(results, 1):
        print("%s %d - %s" % ("ok" if good else "not ok", k, name))
        if not good and why:
            print("# " + str(why).replace("\n", "\n# "))
    return 0 if all(r[1] for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
