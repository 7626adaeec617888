#!/usr/bin/env python3
"""The architecture of docs/architecture.md, checked on the source tree:

- includes point one way: experiments -> methods -> common; common includes
  nothing of methods/ or experiments/, methods/ nothing of experiments/;
- common/ stands in rooms, one floor each, bottom-up in the order of the
  subdir() calls of common/meson.build: every source of common/ lies in a
  room, no two rooms hold a header of the same name, and a room's files
  include only headers of their own room and the rooms below it;
- a backend never includes another backend's header;
- outside a per-method benchmark (experiments/bench/), no file of
  experiments/ or python/ (the Python module's C interface, a floor beside
  experiments/) includes a backend's own header (only methods/method.h);
- inside every folder of common/, methods/, experiments/ and python/, files stand in
  layers (tests/layers.py: no two files use each other, directly or
  around a loop), and a file of a room of common/ calls no function of a
  room above it.

usage: architecture.py SOURCE_ROOT. Exit 1 listing every breach, else 0.
"""
import os
import re
import subprocess
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def sources(root, top):
    for d, _, files in os.walk(os.path.join(root, top)):
        for f in files:
            if f.endswith((".c", ".h")):
                yield os.path.join(d, f)


def headers_of(root, top):
    """Header base names under top, with the folder each lives in."""
    out = {}
    for p in sources(root, top):
        if p.endswith(".h"):
            out.setdefault(os.path.basename(p), os.path.relpath(os.path.dirname(p), root))
    return out


SUBDIR = re.compile(r"^\s*subdir\(\s*'([^']+)'\s*\)", re.M)


def rooms_of(root):
    """The rooms of common/, bottom-up: the order of common/meson.build's
    subdir() calls (a room's library depends on those before it)."""
    with open(os.path.join(root, "common", "meson.build"), encoding="utf-8") as fh:
        return SUBDIR.findall(fh.read())


def check_rooms(root):
    bad = []
    rooms = rooms_of(root)
    if not rooms:
        return ["common/meson.build names no room (subdir)"]
    floor, owner = {}, {}
    for k, room in enumerate(rooms):
        if not os.path.isdir(os.path.join(root, "common", room)):
            bad.append("common/meson.build: room %s has no folder" % room)
            continue
        floor[room] = k
        for p in sources(root, os.path.join("common", room)):
            base = os.path.basename(p)
            if base.endswith(".h"):
                if base in owner:
                    bad.append("header %s in rooms %s and %s" % (base, owner[base], room))
                owner.setdefault(base, room)
    for p in sources(root, "common"):
        parts = os.path.relpath(p, root).split(os.sep)
        if len(parts) < 3 or parts[1] not in floor:
            bad.append("%s lies in no room of common/meson.build" % os.path.relpath(p, root))
            continue
        room = parts[1]
        with open(p, encoding="utf-8") as fh:
            incs = INCLUDE.findall(fh.read())
        for inc in incs:
            other = owner.get(os.path.basename(inc))
            if other and floor[other] > floor[room]:
                bad.append("%s (room %s) includes %s of room %s, a floor up"
                           % (os.path.relpath(p, root), room, inc, other))
    return bad


def check_includes(root):
    bad = []
    common_h = headers_of(root, "common")
    method_h = headers_of(root, "methods")
    exp_h = headers_of(root, "experiments")
    backends = sorted(d for d in os.listdir(os.path.join(root, "methods"))
                      if os.path.isdir(os.path.join(root, "methods", d)))
    for top in ("common", "methods", "experiments", "python"):
        for p in sources(root, top):
            rel = os.path.relpath(p, root)
            parts = rel.split(os.sep)
            with open(p, encoding="utf-8") as fh:
                incs = INCLUDE.findall(fh.read())
            for inc in incs:
                base = os.path.basename(inc)
                head = inc.split("/")[0] if "/" in inc else None
                if top == "common" and base not in common_h:
                    bad.append("%s includes %s, outside common/" % (rel, inc))
                if top == "methods":
                    if base in exp_h and base not in common_h and base not in method_h:
                        bad.append("%s includes %s of experiments/" % (rel, inc))
                    mine = parts[1] if len(parts) > 2 else None
                    owner = head if head in backends else None
                    if owner is None and base in method_h:
                        d = method_h[base].split(os.sep)
                        owner = d[1] if len(d) > 1 else None
                    if owner and owner != mine and base not in common_h:
                        bad.append("%s includes %s of backend %s" % (rel, inc, owner))
                if top in ("experiments", "python") and "bench" not in parts[1:-1]:
                    owner = head if head in backends else None
                    if owner is None and base in method_h and base != "method.h":
                        d = method_h[base].split(os.sep)
                        owner = d[1] if len(d) > 1 else None
                    if owner:
                        bad.append("%s includes %s of backend %s (only experiments/bench/ may)"
                                   % (rel, inc, owner))
    return bad


def check_layers(root):
    bad = []
    layers = os.path.join(os.path.dirname(os.path.abspath(__file__)), "layers.py")
    rooms = [os.path.join("common", r) for r in rooms_of(root)]
    rooms = [d for d in rooms if os.path.isdir(os.path.join(root, d))]
    r = subprocess.run([sys.executable, layers] + rooms, capture_output=True, text=True, cwd=root)
    if rooms and r.returncode:
        bad.append("common: %s" % "\n".join(l for l in r.stdout.splitlines()
                                             if l.startswith(("up a floor", "cycle", "  "))))
    for top in ("common", "methods", "experiments", "python"):
        for d, _, files in os.walk(os.path.join(root, top)):
            if os.path.relpath(d, root) in rooms or not any(f.endswith(".c") for f in files):
                continue
            r = subprocess.run([sys.executable, layers, d], capture_output=True, text=True)
            if r.returncode:
                bad.append("%s: %s" % (os.path.relpath(d, root), r.stdout.strip()))
    return bad


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    bad = check_includes(argv[1]) + check_rooms(argv[1]) + check_layers(argv[1])
    for b in bad:
        print(b)
    print("%d breaches of the architecture" % len(bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
