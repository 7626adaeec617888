#!/usr/bin/env python3
"""Every scene key the docs name as `[section] key` exists: a common section's
key in common/scene/scene.c's key lists, a method section's in that method's
parameter table (`grano methods`). Also: no help text shows `run run`.

usage: docs_keys.py GRANO SOURCE_ROOT
"""
import glob
import os
import re
import subprocess
import sys


def known_keys(grano, root):
    with open(os.path.join(root, "common", "scene", "scene.c"), encoding="utf-8") as f:
        src = f.read()
    keys = {}
    for sec, body in re.findall(r"keys_(\w+)\[\] = \{(.*?)NULL\}", src, re.S):
        keys[sec] = set(re.findall(r'"(\w+)"', body))
    out = subprocess.run([grano, "methods"], capture_output=True, text=True, check=True).stdout
    for sec, table in re.findall(r"^  \[(\w+)\] parameters:\n(.*?)(?:\n\n|\Z)", out, re.M | re.S):
        keys[sec] = set(re.findall(r"^    (\w+) ", table, re.M)) - {"key"}
    return keys


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    grano, root = argv[1], argv[2]
    keys = known_keys(grano, root)
    bad = 0
    pages = glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True)
    for page in pages + [os.path.join(root, "README.md")]:
        with open(page, encoding="utf-8") as f:
            text = f.read()
        for sec, key in set(re.findall(r"`\[(\w+)\] (\w+)", text)):
            # [species.big] style names share their kind's keys; [wall.*] too.
            if sec in keys and key not in keys[sec]:
                print("not ok - %s: `[%s] %s` is not a key of [%s]" % (os.path.relpath(page, root), sec, key, sec))
                bad += 1
    for prog in (os.path.join(root, "grano.sh"),):
        with open(prog, encoding="utf-8") as f:
            if re.search(r"\brun run\b", f.read()):
                print("not ok - %s: a help text shows 'run run'" % os.path.relpath(prog, root))
                bad += 1
    print("%s - scene keys named in the docs exist (%d pages)" % ("ok" if not bad else "not ok", len(pages) + 1))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
