#!/usr/bin/python3
"""Bad input to grano, as a table: every row is an input (scene text, other
files, arguments), the exit code expected and fragments its message must
hold; a refusal (exit 2) must leave no result, checkpoint or snapshot.
Rows marked with an issue-18 defect number failed before that defect's fix.
TAP output. Usage: bad_input.py GRANO"""
import os
import subprocess
import sys
import tempfile

GRANO = sys.argv[1]

GOOD = """[domain]
width = 10
height = 10
[species]
count = 20
[init]
kind = random
[run]
until = 0.01
"""


def with_lines(extra_init="", extra_run="", extra=""):
    return GOOD.replace("kind = random\n", "kind = random\n" + extra_init).replace(
        "until = 0.01\n", "until = 0.01\n" + extra_run) + extra


FILE_SCENE = """[domain]
width = 10
height = 10
[species]
count = {count}
[init]
kind = file
file = {file}
[run]
until = 0.01
"""

# (name, scene text or None, files {name: text}, args (scene is "S",
#  outputs under "O"), expected code, message fragments)
ROWS = [
    # defect 3: intervals far below the time step, or asking for 1e11 samples
    ("3: observe_every = 1e-300", with_lines(extra_run="observe_every = 1e-300\n"), {}, [], 2,
     ["S:10:", "'observe_every'", "samples"]),
    ("3: output_every tiny", with_lines(extra_run="output_every = 1e-12\n"), {}, [], 2,
     ["'observe_every'", "samples"]),
    ("3: checkpoint_every tiny", with_lines(extra_run="checkpoint_every = 1e-12\n"), {}, [], 2,
     ["S:10:", "'checkpoint_every'"]),
    # defect 5: long lines keep their numbers
    ("5: a long comment line does not shift line numbers",
     with_lines(extra_init="; " + "x" * 400 + "\nv0 = 1" + " " * 300 + "\nbogus = 1\n"), {}, [], 2,
     ["S:10:", "'bogus'"]),
    ("5: a long file = path is read whole",
     FILE_SCENE.format(count=3, file="./" + "d/../" * 60 + "g.txt"), {"g.txt": "1 1\n3 3\n5 5\n", "d/keep": ""},
     [], 0, []),
    # defect 6: outside the domain
    ("6: init region outside the domain", with_lines(extra_init="region = 0 0 100 100\n"), {}, [], 2,
     ["S:8:", "'region'", "outside the domain"]),
    ("6: measurement window outside the domain", with_lines(extra="[measure]\nwindow = 50 50 60 60\n"),
     {}, [], 2, ["S:11:", "'window'", "outside the domain"]),
    ("6: a grain of the file outside the domain", FILE_SCENE.format(count=2, file="g.txt"),
     {"g.txt": "1 1\n30 3\n"}, [], 2, ["g.txt", "grain 2", "outside the domain"]),
    # defect 7: a directory or a special file as --out, even with --force
    ("7: --out a directory, --force", GOOD, {"dir/keep": ""}, ["--out", "dir", "--force"], 2,
     ["--out", "'dir'", "directory"]),
    ("7: --out a fifo, --force", GOOD, {"fifo": None}, ["--out", "fifo", "--force"], 2,
     ["--out", "'fifo'", "special file"]),
    # defect 8: an existing checkpoint
    ("8: an existing checkpoint without --force", GOOD, {"O.ckpt": "precious"}, [], 2,
     ["O.ckpt", "--force"]),
    # defect 9
    ("9: '= value' without a key", GOOD.replace("height = 10\n", "height = 10\n= 5\n"), {}, [], 2,
     ["S:4:", "without a key"]),
    ("9: --seed ''", GOOD, {}, ["--seed", ""], 2, ["--seed", "''"]),
    ("9: --seed abc", GOOD, {}, ["--seed", "abc"], 2, ["--seed", "'abc'"]),
    # defect 10: the species count against the file
    ("10: kind = file with a different count", FILE_SCENE.format(count=20, file="g.txt"),
     {"g.txt": "1 1\n3 3\n5 5\n"}, [], 2, ["S:5:", "'count'", "20 grains", "holds 3"]),
    # defect 11: the snapshot path checked first
    ("11: --snapshot in a missing folder", GOOD, {}, ["--snapshot", "nowhere/x.png"], 2,
     ["--snapshot", "nowhere/x.png"]),
    # defect 12: overflow and absurd magnitudes
    ("12: count beyond the grain limit", GOOD.replace("count = 20", "count = 9223372036854775807"), {}, [],
     2, ["S:5:", "'count'", "more than 10000000"]),
    ("12: two species summing past the limit",
     GOOD.replace("[species]\ncount = 20", "[species.a]\ncount = 9000000000000000000\n[species.b]\ncount = 9000000000000000000"),
     {}, [], 2, ["'count'", "more than"]),
    ("12: gravity = 1e300", GOOD.replace("height = 10\n", "height = 10\ngravity = 1e300\n"), {}, [], 2,
     ["S:4:", "'gravity'", "overflow"]),
    ("12: v0 = 1e300", with_lines(extra_init="velocity = gaussian\nv0 = 1e300\n"), {}, [], 2,
     ["S:9:", "'v0'"]),
    ("12: width = 1e300", GOOD.replace("width = 10", "width = 1e300"), {}, [], 2, ["S:2:", "'width'"]),
    ("12: a wall end at 1e300", with_lines(extra="[wall.a]\nfrom = 0 0\nto = 1e300 0\n"), {}, [], 2,
     ["S:12:", "'to'"]),
    # defect 13: endless or binary grain files, and scene files
    ("13: file = /dev/zero", FILE_SCENE.format(count=3, file="/dev/zero"), {}, [], 2,
     ["S:8:", "'file'", "not a regular file"]),
    ("13: a binary grains file", FILE_SCENE.format(count=3, file="bin.dat"), {"bin.dat": "\x01\x02" * 700},
     [], 2, ["bin.dat:1:"]),
    ("13: the scene is /dev/zero", None, {}, ["/dev/zero"], 2, ["/dev/zero", "device"]),
    ("13: a NUL byte in the scene", GOOD.replace("[run]", "[run]\x00"), {}, [], 2, ["S:8:", "NUL"]),
    # defect 18: every scene error names file:line:key
    ("18: missing width names the [domain] line", "[species]\ncount = 3\n[domain]\nheight = 5\n", {}, [], 2,
     ["S:3:", "'width'"]),
    ("18: silo without orifice names the [silo] line",
     GOOD + "[silo]\nwidth = 5\nheight = 5\nbase = 1\n", {}, [], 2, ["S:10:", "'orifice'"]),
    # defect 20: cvode refused before any output exists
    ("20: dem cvode refused up front", with_lines(extra="[dem]\nintegrator = cvode\n"), {}, ["--method", "dem"],
     2, ["S:11:", "'integrator'", "cannot be checkpointed"]),
    # existing refusals
    ("unknown key, nearest suggested", GOOD.replace("count = 20", "count = 20\ndiamter = 1"), {}, [], 2,
     ["S:6:", "did you mean 'diameter'"]),
    ("a key set twice", GOOD.replace("count = 20", "count = 20\ncount = 3"), {}, [], 2, ["S:6:", "twice"]),
    ("unclosed section header", GOOD.replace("[init]", "[init"), {}, [], 2, ["S:6:", "']'"]),
    ("existing --out without --force", GOOD, {"O.h5": "precious"}, [], 2, ["--out", "--force"]),
    ("unknown option", GOOD, {}, ["--frobnicate"], 2, ["--frobnicate"]),
    ("missing scene", None, {}, ["nothere.ini"], 2, ["nothere.ini", "cannot read"]),
]


def run_row(tmp, name, scene, files, args, code, frags):
    os.makedirs(tmp, exist_ok=True)
    for fname, text in files.items():
        path = os.path.join(tmp, fname.replace("O.", "out."))
        os.makedirs(os.path.dirname(path), exist_ok=True)
        if text is None:
            os.mkfifo(path)
        else:
            with open(path, "w") as f:
                f.write(text)
    spath = os.path.join(tmp, "s.ini")
    if scene is not None:
        with open(spath, "w") as f:
            f.write(scene)
    argv = [GRANO, "run"]
    if scene is not None:
        argv.append(spath)
    argv += [a for a in args]
    if "--out" not in args:
        argv += ["--out", os.path.join(tmp, "out.h5")]
    argv.append("-q")
    try:
        p = subprocess.run(argv, cwd=tmp, capture_output=True, text=True, errors="replace", timeout=60)
    except subprocess.TimeoutExpired:
        return "timed out (60 s)"
    err = p.stderr.replace(spath, "S").replace(os.path.join(tmp, "out."), "O.")
    why = []
    if p.returncode != code:
        why.append("exit %d, expected %d" % (p.returncode, code))
    for fr in frags:
        if fr not in err:
            why.append("message lacks %r" % fr)
    if code == 2:
        for left in ("out.h5", "nowhere/x.png"):
            if os.path.exists(os.path.join(tmp, left)) and left.replace("out.", "O.") not in files:
                why.append("%s was written" % left)
        if os.path.exists(os.path.join(tmp, "out.ckpt")) and "O.ckpt" not in files:
            why.append("out.ckpt was written")
    return "; ".join(why) + ("\n" + err if why else "")


def main():
    fails = 0
    with tempfile.TemporaryDirectory() as base:
        for i, row in enumerate(ROWS, 1):
            why = run_row(os.path.join(base, "r%d" % i), *row)
            if why:
                fails += 1
                print("not ok %d - %s: %s" % (i, row[0], why.replace("\n", "\n# ")))
            else:
                print("ok %d - %s" % (i, row[0]))
    print("1..%d" % len(ROWS))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
