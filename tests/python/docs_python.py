#!/usr/bin/env python3
"""docs/python.md shows what the module does today: each ```python block
that an output block follows directly is run (in order, in one namespace,
in a scratch folder that sees the source's experiments/), and what it
prints, or the exception it raises as "Type: message", must be that
output, line for line (trailing spaces aside).

usage: docs_python.py GRANO SOURCE_ROOT WORKDIR (TAP)
"""
import contextlib
import io
import os
import re
import sys
import warnings

from common import Tap, setup

BLOCK = re.compile(r"```python\n(.*?)```\n```\n(.*?)```", re.S)


def main(argv):
    exe, root, work = setup(argv)
    if not os.path.exists("experiments"):
        os.symlink(os.path.join(root, "experiments"), "experiments")
    with open(os.path.join(root, "docs", "python.md"), encoding="utf-8") as f:
        pairs = BLOCK.findall(f.read())
    tap = Tap()
    ns = {}
    warnings.simplefilter("ignore")
    for code, want in pairs:
        out = io.StringIO()
        with contextlib.redirect_stdout(out):
            try:
                exec(compile(code, "docs/python.md", "exec"), ns)
            except Exception as e:  # the block shows the exception it raises
                print("%s: %s" % (type(e).__name__, e))
        got = [l.rstrip() for l in out.getvalue().rstrip("\n").splitlines()]
        want = [l.rstrip() for l in want.rstrip("\n").splitlines()]
        first = code.strip().splitlines()[-1][:60]
        tap.check(got == want, "docs/python.md: %s" % first,
                  "printed:\n%s\nthe page shows:\n%s" % ("\n".join(got), "\n".join(want)))
    tap.check(len(pairs) >= 8, "docs/python.md has %d code blocks with their output" % len(pairs))
    return tap.finish()


if __name__ == "__main__":
    sys.exit(main(sys.argv))
