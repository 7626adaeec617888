#!/usr/bin/env python3
"""Each method's observables as `grano methods` prints them from its declared
table equal the table of its page's "## Observables" section
(docs/methods/NAME.md): the same names, in the same order, with the same
units, kinds and validity keys.

usage: docs_observables.py GRANO SOURCE_ROOT
"""
import os
import re
import subprocess
import sys

ROW = re.compile(r"^    (\w+) +(.+?) +(scalar|vector|count) +(.*)$")


def declared(grano):
    out = subprocess.run([grano, "methods"], capture_output=True, text=True, check=True).stdout
    methods = {}
    for block in out.split("\n\n"):
        name = block.split(":", 1)[0].strip()
        m = re.search(r"^  observables .*?\n(.*?)^  \[", block, re.M | re.S)
        if not m:
            continue
        rows = []
        for line in m.group(1).splitlines():
            r = ROW.match(line)
            if r:
                key = re.search(r"\[validity limit: (\S+)\]", r.group(4))
                rows.append((r.group(1), r.group(2), r.group(3), key.group(1) if key else ""))
        methods[name] = rows
    return methods


def documented(page):
    with open(page, encoding="utf-8") as f:
        text = f.read()
    m = re.search(r"^## Observables\b.*?\n(.*?)(?=^## |\Z)", text, re.M | re.S)
    if not m:
        return None
    rows = []
    for line in m.group(1).splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) >= 5 and cells[0].startswith("`"):
            key = re.search(r"`(\w+\.\w+)`", cells[4])
            rows.append((cells[0].strip("`"), cells[1].strip("`"), cells[2], key.group(1) if key else ""))
    return rows


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    grano, root = argv[1], argv[2]
    bad = 0
    decl = declared(grano)
    if not decl:
        print("not ok - grano methods lists no observables")
        return 1
    for name, rows in sorted(decl.items()):
        page = os.path.join(root, "docs", "methods", name + ".md")
        doc = documented(page) if os.path.exists(page) else None
        if doc is None:
            print("not ok - %s: no '## Observables' section in %s" % (name, os.path.relpath(page, root)))
            bad += 1
        elif doc != rows:
            print("not ok - %s: the page's observables differ from the declared ones" % name)
            for a, b in zip(rows + [None] * len(doc), doc + [None] * len(rows)):
                if a != b:
                    print("#   declared %s, page %s" % (a, b))
                    break
            bad += 1
        else:
            print("ok - %s: %d observables, page and table equal" % (name, len(rows)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
