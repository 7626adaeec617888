#!/usr/bin/python3
"""Mutated shipped scenes run by grano (seeded): lines deleted, duplicated
or cut, numbers replaced by extremes, bytes flipped. Every mutant must end
with exit 0 (a valid scene), 1 (a run stopped with a diagnostic) or 2 (bad
input naming file:line, a flag or the file) within the time limit; a signal
or a hang fails. TAP output with the figures.
Usage: mutants.py GRANO SRC COUNT SEED"""
import glob
import os
import random
import re
import subprocess
import sys
import tempfile

GRANO, SRC, COUNT, SEED = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
EXTREMES = ["0", "-1", "1e300", "-1e300", "nan", "inf", "1e-300", "9223372036854775807", "abc", "", "1e99",
            "0.5", "3", "1e6"]


def mutate(lines, rng):
    lines = list(lines)
    for _ in range(rng.randint(1, 3)):
        k = rng.randrange(len(lines))
        op = rng.randrange(6)
        if op == 0:
            del lines[k]
        elif op == 1:
            lines.insert(k, lines[k])
        elif op == 2:
            lines[k] = lines[k][:rng.randrange(len(lines[k]) + 1)]
        elif op == 3:
            nums = list(re.finditer(r"-?\d+(\.\d+)?(e-?\d+)?", lines[k]))
            if nums:
                m = rng.choice(nums)
                lines[k] = lines[k][:m.start()] + rng.choice(EXTREMES) + lines[k][m.end():]
        elif op == 4 and lines[k]:
            i = rng.randrange(len(lines[k]))
            lines[k] = lines[k][:i] + chr(rng.randrange(1, 127)) + lines[k][i + 1:]
        else:
            lines.insert(k, lines[rng.randrange(len(lines))])
        if not lines:
            lines = [""]
    return lines


def main():
    rng = random.Random(SEED)
    scenes = sorted(glob.glob(os.path.join(SRC, "experiments", "scenes", "*.ini")))
    texts = {s: open(s).read().splitlines() for s in scenes}
    counts = {0: 0, 1: 0, 2: 0}
    bad = []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(COUNT):
            src = rng.choice(scenes)
            path = os.path.join(tmp, "m%d.ini" % i)
            with open(path, "w") as f:
                f.write("\n".join(mutate(texts[src], rng)) + "\n")
            out = os.path.join(tmp, "m.h5")
            try:
                p = subprocess.run([GRANO, "run", path, "--until", "0.002", "-o", out, "-q", "--force"],
                                   capture_output=True, text=True, errors="replace", timeout=60)
            except subprocess.TimeoutExpired:
                bad.append((i, os.path.basename(src), "hang (60 s)"))
                continue
            rc = p.returncode
            if rc not in counts:
                bad.append((i, os.path.basename(src), "exit %d: %s" % (rc, p.stderr[-300:])))
                continue
            counts[rc] += 1
            if rc == 2 and not re.search(r"m%d\.ini(:\d+)?|--|/" % i, p.stderr):
                bad.append((i, os.path.basename(src), "refusal names no file or flag: " + p.stderr[-300:]))
            os.unlink(path)
    print("%s 1 - %d mutants of %d scenes: exit 0 %d, exit 1 %d, exit 2 %d, crashes or hangs %d"
          % ("ok" if not bad else "not ok", COUNT, len(scenes), counts[0], counts[1], counts[2], len(bad)))
    for b in bad[:20]:
        print("# mutant %d of %s: %s" % b)
    print("1..1")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
