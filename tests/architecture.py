#!/usr/bin/env python3
"""The architecture of DESIGN.md, checked on the source tree (issue 12):

- includes point one way: experiments -> methods -> common; common includes
  nothing of methods/ or experiments/, methods/ nothing of experiments/;
- a backend never includes another backend's header;
- outside a per-method benchmark (experiments/bench/), no file of
  experiments/ includes a backend's own header (only methods/method.h);
- inside every folder of common/, methods/ and experiments/, files stand in
  layers (tests/layers.py: no two files use each other, directly or
  around a loop).

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


def check_includes(root):
    bad = []
    common_h = headers_of(root, "common")
    method_h = headers_of(root, "methods")
    exp_h = headers_of(root, "experiments")
    backends = sorted(d for d in os.listdir(os.path.join(root, "methods"))
                      if os.path.isdir(os.path.join(root, "methods", d)))
    for top in ("common", "methods", "experiments"):
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
                if top == "experiments" and "bench" not in parts[1:-1]:
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
    for top in ("common", "methods", "experiments"):
        for d, _, files in os.walk(os.path.join(root, top)):
            if not any(f.endswith(".c") for f in files):
                continue
            r = subprocess.run([sys.executable, layers, d], capture_output=True, text=True)
            if r.returncode:
                bad.append("%s: %s" % (os.path.relpath(d, root), r.stdout.strip()))
    return bad


def main(argv):
    if len(argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    bad = check_includes(argv[1]) + check_layers(argv[1])
    for b in bad:
        print(b)
    print("%d breaches of the architecture" % len(bad))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
