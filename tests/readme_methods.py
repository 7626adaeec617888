#!/usr/bin/env python3
"""The README's table of methods that run today names exactly the registered
backends (`grano methods`), each with its docs page present.

usage: readme_methods.py GRANO SOURCE_ROOT
"""
import os
import re
import subprocess
import sys


def main(argv):
    if len(argv) != 3:
        sys.exit(__doc__)
    out = subprocess.run([argv[1], "methods"], capture_output=True, text=True, check=True).stdout
    registered = set(re.findall(r"^(\w+): ", out, re.M))
    with open(os.path.join(argv[2], "README.md"), encoding="utf-8") as f:
        rows = re.findall(r"^\| [^|]+ \| `(\w+)` \| `(docs/methods/\w+\.md)` \|$", f.read(), re.M)
    listed = {m for m, _ in rows}
    bad = 0
    for m in sorted(registered - listed):
        print("not ok - method '%s' is registered but not in the README's table" % m)
        bad += 1
    for m in sorted(listed - registered):
        print("not ok - the README lists '%s', which is not registered" % m)
        bad += 1
    for m, page in rows:
        if not os.path.exists(os.path.join(argv[2], page)):
            print("not ok - %s: no page %s" % (m, page))
            bad += 1
    print("%s - README lists %s; registry has %s" % ("ok" if not bad else "not ok",
                                                     sorted(listed), sorted(registered)))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
