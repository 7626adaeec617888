#!/usr/bin/python3
"""grano plot and grano movie on a short run of each method.

For dem, edmd, cd, dsmc (grains) and lgca (its packing fraction field):
the PNG is a PNG of the size the box gives, its script's colour range is
the 2nd to 98th percentile of the values drawn as numpy computes them from
the file (h5py), its title carries the frame's time; --frame, --time,
--percentiles, --range, --color and --contacts draw what they say (the
contact number and the lines counted from the file's contact rows); bad
input exits 2 naming the flag and writes nothing; a GIF movie has one
image per frame drawn (PIL), a movie asked as MP4 without ffmpeg is
refused saying how to install it.

With --mp4: only the MP4 movie, its frames counted by ffprobe; exit 77
(skipped) without ffmpeg.

usage: pictures_check.py GRANO SOURCE_ROOT WORKDIR [--mp4]
"""
import os
import re
import shutil
import struct
import subprocess
import sys

import h5py
import numpy as np

STACK = """[scene]
name = stack
seed = 1
[domain]
width = 10
height = 12
gravity = 1
[material]
tangential = coulomb
mu = 0.5
restitution = 0
[species]
count = 40
[init]
kind = lattice
region = 0 0 10 6
spacing = 1
velocity = zero
[run]
until = 0.5
output_every = 0.125
contacts = yes
"""

checks = []


def check(good, what, why=""):
    checks.append((bool(good), what, why))


def grano(*args, env=None):
    p = subprocess.run([GRANO] + [str(a) for a in args], capture_output=True, text=True, env=env, timeout=300)
    return p.returncode, p.stdout, p.stderr


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def script(path):
    gp = os.path.splitext(path)[0] + ".gp"
    return open(gp, encoding="utf-8").read() if os.path.exists(gp) else ""


def cbrange(text):
    m = re.search(r"^set cbrange \[([^:]+):([^\]]+)\]", text, re.M)
    return (float(m.group(1)), float(m.group(2))) if m else None


def title_time(text):
    m = re.search(r"^set title '.*frame (\d+), t = (\S+) τ'", text, re.M)
    return (int(m.group(1)), float(m.group(2))) if m else None


def percentiles(v, lo=2, hi=98):
    """numpy's, a range of zero width widened as plot.h says."""
    r = np.percentile(v, [lo, hi])
    if not r[1] > r[0]:
        half = max(0.5, 1e-6 * abs(r[0]))
        r = (r[0] - half, r[1] + half)
    return tuple(r)


def close(a, b, tol=1e-6):
    return a is not None and b is not None and all(abs(x - y) <= tol * max(1.0, abs(y)) for x, y in zip(a, b))


def disks_size(w, h):
    s = 800.0 / max(w, h)
    return int(w * s) + 230, int(h * s) + 60


def field_size(w, h):
    if w < 5 * h and h < 5 * w:
        s = 800.0 / max(w, h)
        return int(w * s) + 200, int(h * s) + 60
    return (400, 1000) if w < h else (1000, 400)


def grains(f, k):
    t = f["particles/trajectory"]
    v = t["velocity/value"][k]
    flags = t["flags/value"][k]
    return v, (flags & 5) == 0, t["position/time"][:]


def expected(f, method, k, quantity="speed"):
    """What the picture of frame k colours, and its size."""
    if method == "lgca":
        g = f["fields/packing_fraction"]
        v = g["value"][k].ravel()
        nx, ny = g.attrs["grid"]
        cw, ch = g.attrs["cell"]
        return v[np.isfinite(v)], field_size(nx * cw, ny * ch), g["time"][:]
    v, mobile, times = grains(f, k)
    q = {"speed": np.hypot(v[:, 0], v[:, 1]), "vy": v[:, 1]}[quantity]
    box = f["particles/trajectory/box/edges/value"][k]
    return q[mobile], disks_size(*box), times


def contact_numbers(f, k):
    """Contacts per mobile grain (walls included) and grain-grain lines of frame k."""
    c = f["contacts"]
    first, n = int(c["count"][:k].sum()), int(c["count"][k])
    i, j = c["i"][first:first + n], c["j"][first:first + n]
    ids = f["particles/trajectory/id"][:]
    flags = f["particles/trajectory/flags/value"][k]
    where = {int(g): x for x, g in enumerate(ids)}
    z = np.zeros(len(ids))
    for a, b in zip(i, j):
        z[where[int(a)]] += 1
        if b >= 0:
            z[where[int(b)]] += 1
    lines = int(sum(1 for a, b in zip(i, j) if b >= 0 and not (flags[where[int(a)]] | flags[where[int(b)]]) & 4))
    return z[(flags & 5) == 0], lines


def run_methods(work, only=None):
    scenes = os.path.join(SRC, "experiments", "scenes")
    stack = os.path.join(work, "stack.ini")
    with open(stack, "w") as fh:
        fh.write(STACK)
    runs = {
        "dem": [os.path.join(scenes, "box.ini"), "--until", "0.5", "--set", "run.output_every=0.125",
                "--set", "run.contacts=yes"],
        "edmd": [os.path.join(scenes, "box.ini"), "--until", "0.5", "--set", "run.output_every=0.125"],
        "cd": [stack],
        "dsmc": [os.path.join(scenes, "vibrated.ini"), "--until", "1", "--set", "run.output_every=0.25"],
        "lgca": [os.path.join(scenes, "lgca-silo.ini"), "--until", "200", "--set", "run.output_every=50"],
    }
    out = {}
    for m, args in runs.items():
        if only and m not in only:
            continue
        h5 = os.path.join(work, m + ".h5")
        rc, _, err = grano("run", *args, "--method", m, "--out", h5, "--force", "-q")
        check(rc == 0, "%s: a short run writes %s" % (m, os.path.basename(h5)), err)
        out[m] = h5
    return out


def each_method(work, results):
    for m, h5 in results.items():
        png = os.path.join(work, m + "-last.png")
        rc, so, err = grano("plot", h5, png)
        text = script(png)
        with h5py.File(h5, "r") as f:
            vals, size, times = expected(f, m, -1)
        check(rc == 0 and so.strip() == png, "%s: grano plot prints OUT" % m, err)
        check(png_size(png) == size and ("# size %d %d" % size) in text,
              "%s: a PNG of %s pixels, as the box gives (got %s)" % (m, size, png_size(png)), err)
        want = percentiles(vals)
        check(close(cbrange(text), want), "%s: colour range %s is the 2nd to 98th percentile of the %d values %s"
              % (m, cbrange(text), len(vals), want))
        tt = title_time(text)
        check(tt and tt[0] == len(times) - 1 and close([tt[1]], [times[-1]], 1e-3),
              "%s: the title names the last frame and its time %g (%s)" % (m, times[-1], tt))
        check("2nd to 98th percentile" in text, "%s: the colour bar says the scale is a percentile one" % m)


def selection(work, h5):
    with h5py.File(h5, "r") as f:
        times = f["particles/trajectory/position/time"][:]
        vals1, _, _ = expected(f, "dem", 1)
        vy, _, _ = expected(f, "dem", -1, "vy")
        z, lines = contact_numbers(f, len(times) - 1)
    for args, k, what in [(["--frame", "1"], 1, "--frame 1"), (["--frame", "-2"], len(times) - 2, "--frame -2"),
                          (["--time", str(times[2] + 0.01)], 2, "--time near frame 2"),
                          (["--time", "1e9"], len(times) - 1, "--time past the end: the last")]:
        png = os.path.join(work, "sel.png")
        rc, _, err = grano("plot", h5, png, *args)
        tt = title_time(script(png))
        check(rc == 0 and tt and tt[0] == k and close([tt[1]], [times[k]], 1e-3),
              "%s draws frame %d, t = %g (title: %s)" % (what, k, times[k], tt), err)
    png = os.path.join(work, "p.png")
    rc, _, err = grano("plot", h5, png, "--frame", "1", "--percentiles", "10,90")
    text = script(png)
    check(rc == 0 and close(cbrange(text), percentiles(vals1, 10, 90)) and "10th to 90th percentile" in text,
          "--percentiles 10,90: the 10th and 90th percentiles, said on the bar", err)
    rc, _, err = grano("plot", h5, png, "--range", "0.5,2")
    check(rc == 0 and cbrange(script(png)) == (0.5, 2.0) and "percentile" not in script(png),
          "--range 0.5,2: cbrange [0.5:2]", err)
    rc, _, err = grano("plot", h5, png, "--color", "vy")
    check(rc == 0 and close(cbrange(script(png)), percentiles(vy)) and "v_y" in script(png),
          "--color vy: percentiles of vy", err)
    rc, _, err = grano("plot", h5, png, "--color", "contacts", "--contacts")
    text = script(png)
    nl = sum(len(b.strip().splitlines()) for b in re.findall(r"^\$net\d << EOD\n(.*?)^EOD", text, re.M | re.S))
    check(rc == 0 and close(cbrange(text), percentiles(z)) and nl == lines and lines > 0,
          "--color contacts --contacts: contact numbers from the file's rows, %d lines drawn (%d)" % (lines, nl), err)
    for fmt, magic in [("svg", b"<?xml"), ("pdf", b"%PDF")]:
        rc, so, err = grano("plot", h5, "--format", fmt)
        out = so.strip()
        ok = rc == 0 and out.endswith("-frame%d.%s" % (len(times) - 1, fmt)) and os.path.exists(out)
        check(ok and open(out, "rb").read(len(magic)) == magic, "--format %s: %s" % (fmt, os.path.basename(out)), err)


def refusals(work, results):
    junk = os.path.join(work, "table.h5")
    with h5py.File(junk, "w") as f:
        f["cases/x/value"] = [1.0, 2.0]
    out = os.path.join(work, "refused.png")
    cases = [(["plot", results["dem"], out, "--color", "bogus"], "--color"),
             (["plot", results["edmd"], out, "--color", "contacts"], "--color contacts"),
             (["plot", results["dem"], out, "--color", "stress"], "--field stress"),
             (["plot", results["dem"], out, "--field", "bogus"], "--field"),
             (["plot", results["lgca"], out, "--color", "speed"], "--color"),
             (["plot", results["dem"], out, "--frame", "99"], "--frame"),
             (["plot", results["dem"], out, "--percentiles", "50,20"], "--percentiles"),
             (["plot", results["dem"], out, "--range", "1"], "--range"),
             (["plot", results["dem"], out, "--bogus"], "--bogus"),
             (["plot", results["dem"], os.path.join(work, "x.jpg")], ".png"),
             (["plot", os.path.join(work, "missing.h5"), out], "no such file"),
             (["plot", junk, out], "not a grano result"),
             (["movie", results["dem"], os.path.join(work, "m.avi")], ".mp4 or .gif"),
             (["movie", results["dem"], os.path.join(work, "m.gif"), "--from", "5"], "--from"),
             (["movie", results["dem"], os.path.join(work, "m.gif"), "--fps", "0"], "--fps")]
    for args, name in cases:
        rc, _, err = grano(*args)
        left = [p for p in (out, os.path.join(work, "m.gif")) if os.path.exists(p)]
        shown = " ".join(os.path.basename(a) if os.sep in a else a for a in args)
        check(rc == 2 and name in err and not left, "%s: exit 2 naming %s, nothing written" % (shown, name), err)


try:
    from PIL import Image
except ImportError:
    Image = None


def gif_frames(path):
    """Images in a GIF (None without PIL)."""
    if Image is None:
        return None
    with Image.open(path) as im:
        return im.n_frames


def movies(work, results):
    for h5, args, n, what in [(results["dem"], ["--every", "2"], 3, "dem, --every 2 of 5 frames"),
                              (results["dem"], ["--from", "0.2", "--to", "0.4", "--contacts"], 2,
                               "dem, --from 0.2 --to 0.4 with the network"),
                              (results["lgca"], [], 5, "lgca, its field")]:
        gif = os.path.join(work, "m.gif")
        rc, so, err = grano("movie", h5, gif, *args)
        frames = gif_frames(gif) if rc == 0 else -1
        left = [p for p in os.listdir(work) if ".frames-" in p or p.endswith(".part")]
        check(rc == 0 and so.strip() == "%s: %d frames" % (gif, n) and frames in (n, None) and not left,
              "movie to GIF (%s): %s images%s" % (what, frames, "" if Image else " (PIL missing: not counted)"),
              err)
    gnuplot = shutil.which("gnuplot")
    if gnuplot:
        bare = os.path.join(work, "bin")
        os.makedirs(bare, exist_ok=True)
        if not os.path.exists(os.path.join(bare, "gnuplot")):
            os.symlink(gnuplot, os.path.join(bare, "gnuplot"))
        mp4 = os.path.join(work, "nope.mp4")
        rc, _, err = grano("movie", results["dem"], mp4, env=dict(os.environ, PATH=bare))
        check(rc == 2 and "apt-get install ffmpeg" in err and ".gif" in err and not os.path.exists(mp4),
              "MP4 without ffmpeg: exit 2, says how to install it or to ask for a .gif", err)


def mp4(work):
    if not shutil.which("ffmpeg") or not shutil.which("ffprobe") or not shutil.which("gnuplot"):
        print("ffmpeg or gnuplot is not installed: skipped")
        return 77
    results = run_methods(work, ["dem"])
    out = os.path.join(work, "m.mp4")
    rc, so, err = grano("movie", results["dem"], out, "--fps", "5")
    p = subprocess.run(["ffprobe", "-v", "error", "-count_frames", "-select_streams", "v:0", "-show_entries",
                        "stream=nb_read_frames,codec_name", "-of", "csv=p=0", out], capture_output=True, text=True)
    left = [x for x in os.listdir(work) if ".frames-" in x or x.endswith(".part")]
    good = rc == 0 and p.stdout.strip() == "h264,5" and not left
    print("%s: movie to MP4: ffprobe says %r (want h264,5)%s" % ("ok" if good else "FAILED", p.stdout.strip(),
                                                                 "" if rc == 0 else ": " + err))
    return 0 if good and all(c[0] for c in checks) else 1


def main(argv):
    global GRANO, SRC
    if len(argv) < 4:
        sys.exit(__doc__)
    GRANO, SRC, work = argv[1], argv[2], argv[3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    if "--mp4" in argv:
        return mp4(work)
    if not shutil.which("gnuplot"):
        print("1..0 # SKIP gnuplot is not installed")
        return 0
    results = run_methods(work)
    if all(c[0] for c in checks):
        each_method(work, results)
        selection(work, results["dem"])
        selection(work, results["cd"])
        refusals(work, results)
        movies(work, results)
    for n, (good, what, why) in enumerate(checks, 1):
        print("%s %d - %s" % ("ok" if good else "not ok", n, what))
        if not good and why:
            print("# " + why.strip().replace("\n", "\n# "))
    print("1..%d" % len(checks))
    return 0 if all(c[0] for c in checks) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
