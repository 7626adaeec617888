#!/usr/bin/python3
"""Runs killed with SIGKILL at random moments (seeded), output and
checkpoint writes included, against what docs/reliability.md promises:
after every kill the checkpoint that exists opens, and so does the result
(with h5py in SWMR read mode, as a killed writer leaves it), holding every
frame a reader saw just before the kill, each sample equal to the same
sample of an uninterrupted run. The run is continued from its checkpoint
until it finishes, and the finished result must equal the uninterrupted
run's bit for bit (same_h5.py: h5diff passes datasets of different
shapes). The rounds go through five scenes: dem with
contacts, stress and fields; edmd and dsmc with stress and fields; cd with
contacts and stress; lgca's pipe. TAP output, the figures on a comment line.
Usage: fault_kill.py GRANO KILLS SEED [JOBS]: JOBS processes share the
kills, each with its own seed (SEED * 1000 + job), and the figures are
summed."""
import glob
import os
import random
import re
import signal
import subprocess
import sys
import tempfile
import time

import h5py
import numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import same_h5  # noqa: E402

GRANO, KILLS, SEED = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
JOBS = int(sys.argv[4]) if len(sys.argv) > 4 else 1
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Checkpoints and frames often, so kills land in both kinds of write.
GRAINS = """[domain]
width = 30
height = 30
gravity = 1
[species]
count = 150
[init]
kind = random
velocity = gaussian
v0 = 1
[measure]
field_cells = 6 6
[run]
until = 1
output_every = 0.01
checkpoint_every = 0.05
stress = yes
"""
SCENES = [
    ("dem", GRAINS + "contacts = yes\n[material]\ntangential = spring\nkn = 1e5\ngamma_n = 100\nmu = 0.5\n"
     "[species]\npolydispersity = 0.1\n"),
    ("edmd", GRAINS + "[material]\nrestitution = 0.9\n"),
    ("cd", GRAINS + "contacts = yes\n[material]\nrestitution = 0.9\nmu = 0.3\n"),
    ("dsmc", GRAINS + "[material]\nrestitution = 0.9\n"),
]


def lgca_scene():
    with open(os.path.join(ROOT, "experiments", "scenes", "lgca-pipe.ini")) as f:
        text = f.read()
    return text.replace("until = 3000", "until = 300").replace(
        "output_every = 100", "output_every = 3\ncheckpoint_every = 15")


def series_rows(f):
    """Complete samples of every time series in f (the fewest rows of its
    step, time and value) and of its contact network."""
    rows = {}
    def visit(name, obj):
        if isinstance(obj, h5py.Group) and "time" in obj and "step" in obj:
            parts = [obj[k] for k in ("step", "time", "value", "count") if k in obj]
            rows[name] = min(d.shape[0] for d in parts)
    f.visititems(visit)
    return rows


def prefix_equal(ref, path):
    """'' if every complete sample of path equals ref's same sample, else
    what differs; with the frames path holds."""
    bad = []
    with h5py.File(ref, "r") as r, h5py.File(path, "r", swmr=True) as q:
        rows = series_rows(q)
        def check(name, obj):
            if not isinstance(obj, h5py.Dataset) or name not in r:
                if isinstance(obj, h5py.Dataset):
                    bad.append(name + ": not in the uninterrupted run's result")
                return
            group = name.rsplit("/", 1)[0] if "/" in name else ""
            a, b = numpy.asarray(r[name][()]), numpy.asarray(obj[()])
            if group in rows and b.ndim and name.rsplit("/", 1)[1] in ("step", "time", "value", "count"):
                n = rows[group]
                a, b = a[:n], b[:n]
            elif group == "contacts":  # i, j, force: the rows the counts claim
                n = int(numpy.sum(q["contacts/count"][:rows.get("contacts", 0)]))
                a, b = a[:n], b[:n]
            elif b.ndim and r[name].maxshape[0] is None:
                return  # a series' shared axis seen through another link
            nan = a.dtype.kind in "fc" and b.dtype.kind in "fc"
            if a.shape != b.shape:
                bad.append("%s: shape %s against %s" % (name, b.shape, a.shape))
            elif not numpy.array_equal(a, b, equal_nan=nan):
                diff = [k for k in range(len(a)) if not numpy.array_equal(a[k], b[k], equal_nan=nan)]
                bad.append("%s: rows %s of %d differ from the uninterrupted run's" % (name, diff[:4], len(a)))
        q.visititems(check)
        frames = rows.get("particles/trajectory/position", rows.get("observables/" + next(
            (k for k in q.get("observables", {})), ""), 0))
    return "; ".join(bad[:3]), frames


def frames_now(path):
    """Samples a reader sees now (0 when the file is not there yet)."""
    try:
        with h5py.File(path, "r", swmr=True) as q:
            rows = series_rows(q)
            return rows.get("particles/trajectory/position", max(rows.values(), default=0))
    except (OSError, KeyError):
        return 0


def kept(ref, ckpt):
    """Samples a restart from ckpt keeps (it drops the later ones, which it
    writes again): the run's counters of samples taken, frames or else
    observables."""
    with h5py.File(ckpt, "r") as c, h5py.File(ref, "r") as r:
        k = c["checkpoint/run_counters"][()]
        return int(k[1] if "particles" in r else k[0])


def ckpt_readable(path):
    if not os.path.exists(path):
        return True
    try:
        with h5py.File(path, "r") as f:
            f.visit(lambda name: None)
        return True
    except Exception:
        return False


def run_round(rng, method, scene, out, ckpt, ref, wall, results):
    """Kill at random moments until the run finishes; (kills, restarts,
    results lost, finished), last stderr."""
    kills = restarts = lost = 0
    for _ in range(60):
        argv = [GRANO, "run", scene, "--method", method, "-o", out, "-q"]
        argv += ["--restart", ckpt] if os.path.exists(ckpt) else ["--force"]
        restarts += "--restart" in argv
        # samples a reader saw before the restart published may be dropped
        keep = kept(ref, ckpt) if os.path.exists(ckpt) else None
        p = subprocess.Popen(argv, stderr=subprocess.PIPE, text=True)
        try:
            err = p.communicate(timeout=rng.uniform(0.0, 0.6 * wall))[1]
            return (kills, restarts, lost, p.returncode == 0), err
        except subprocess.TimeoutExpired:
            seen = frames_now(out)
            seen = min(seen, keep) if keep is not None else seen
            p.send_signal(signal.SIGKILL)
            p.communicate()
            kills += 1
            if not ckpt_readable(ckpt):
                results.append(("%s kill %d: checkpoint readable" % (method, kills), False, ckpt))
            if not os.path.exists(out):
                if seen:
                    lost += 1
                    results.append(("%s kill %d: the result is gone" % (method, kills), False, ""))
                continue
            try:
                why, frames = prefix_equal(ref, out)
            except Exception as e:  # an unreadable result
                why, frames = "%s: %s" % (type(e).__name__, e), -1
            if why or frames < seen:
                lost += 1
                results.append(("%s kill %d: the result holds the %d samples seen before it, "
                                "each as the uninterrupted run's" % (method, kills, seen), False,
                                why or "%d samples after the kill" % frames))
    return (kills, restarts, lost, False), "60 kills without finishing"


def main():
    rng = random.Random(SEED)
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        variants = []
        for method, text in SCENES + [("lgca", lgca_scene())]:
            scene = os.path.join(tmp, method + ".ini")
            with open(scene, "w") as f:
                f.write(text)
            ref = os.path.join(tmp, method + "-ref.h5")
            t0 = time.monotonic()
            subprocess.run([GRANO, "run", scene, "--method", method, "-o", ref, "-q"], check=True,
                           stderr=subprocess.DEVNULL)
            variants.append((method, scene, ref, time.monotonic() - t0))
        out, ckpt = os.path.join(tmp, "k.h5"), os.path.join(tmp, "k.ckpt")
        kills = restarts = lost = rounds = identical = 0
        # Rounds from a fresh start until enough kills, scene after scene:
        # each round is killed until it finishes, then compared.
        while kills < KILLS and rounds < KILLS:
            method, scene, ref, wall = variants[rounds % len(variants)]
            rounds += 1
            for x in [out, ckpt] + glob.glob(out + ".*") + glob.glob(ckpt + ".*"):
                if os.path.exists(x):
                    os.unlink(x)
            ok, err = run_round(rng, method, scene, out, ckpt, ref, wall, results)
            kills += ok[0]
            restarts += ok[1]
            lost += ok[2]
            if not ok[3]:
                results.append(("round %d (%s) finishes" % (rounds, method), False, err))
                break
            # (h5diff would pass datasets of different shapes)
            differ = same_h5.diff(ref, out, ["/particles", "/observables", "/fields", "/contacts"])
            identical += not differ
            results.append(("round %d (%s): %d kills, %d restarts, identical to the uninterrupted run"
                            % (rounds, method, ok[0], ok[1]), not differ, "\n".join(differ[:5])))
        results.append(("results lost to a kill: %d of %d kills" % (lost, kills), lost == 0, ""))
    tests = 0
    for name, good, why in results:
        tests += 1
        print("%s %d - %s" % ("ok" if good else "not ok", tests, name))
        if not good and why:
            print("# " + why.replace("\n", "\n# "))
    print("# figures: kills %d, results lost or unreadable after a kill %d, restarts %d, rounds %d, "
          "equal to the uninterrupted run %d" % (kills, lost, restarts, rounds, identical))
    print("1..%d" % tests)
    return 0 if all(r[1] is not False for r in results) else 1


def jobs():
    """JOBS copies of this test at once, their TAP lines and figures merged."""
    import concurrent.futures
    def one(j):
        return subprocess.run([sys.executable, __file__, GRANO, str((KILLS + JOBS - 1) // JOBS),
                               str(SEED * 1000 + j)], capture_output=True, text=True).stdout
    with concurrent.futures.ThreadPoolExecutor(JOBS) as ex:
        outs = list(ex.map(one, range(JOBS)))
    tests, sums, good = 0, [0] * 5, True
    for j, out in enumerate(outs):
        for line in out.splitlines():
            m = re.match(r"(not ok|ok) \d+ - (.*)", line)
            if m:
                tests += 1
                good &= m.group(1) == "ok"
                print("%s %d - job %d: %s" % (m.group(1), tests, j, m.group(2)))
            elif line.startswith("# figures:"):
                sums = [a + int(b) for a, b in zip(sums, re.findall(r"\d+", line))]
            elif line.startswith("#"):
                print(line)
    print("# figures: kills %d, results lost or unreadable after a kill %d, restarts %d, rounds %d, "
          "equal to the uninterrupted run %d (%d jobs)" % (*sums, JOBS))
    print("1..%d" % tests)
    return 0 if good and tests else 1


if __name__ == "__main__":
    sys.exit(jobs() if JOBS > 1 else main())
