#!/usr/bin/env python3
"""The docs state the present: docs/performance.md stays within 400 lines,
and README.md and docs/**/*.md carry no date, no "session" and no issue
number (git history keeps the diary; a page says what is true today, each
figure beside its command).

usage: docs_present.py SOURCE_ROOT
"""
import glob
import os
import re
import sys

MAX_PERFORMANCE_LINES = 400
MONTHS = r"(?:Jan|Feb|Mar|Apr|May|Jun|Jul|Aug|Sep|Oct|Nov|Dec)[a-z]*\.?"
FORBIDDEN = [
    ("a date", re.compile(r"\b(?:19|20)\d\d-[01]\d(?:-[0-3]\d)?\b")),
    ("a date", re.compile(r"\b" + MONTHS + r" (?:19|20)\d\d\b")),
    ("a date", re.compile(r"\b[0-3]?\d " + MONTHS + r"(?: (?:19|20)\d\d)?\b(?! ?[a-z])")),
    ("the word 'session'", re.compile(r"\bsessions?\b", re.I)),
    ("an issue number", re.compile(r"\bissues? (?:#\s*)?\d+", re.I)),
    ("an issue number", re.compile(r"(?<![\w/&])#\d+\b")),
]


def problems(path, text):
    for n, line in enumerate(text.splitlines(), 1):
        for what, rx in FORBIDDEN:
            m = rx.search(line)
            if m:
                yield "%s:%d: %s (%r)" % (path, n, what, m.group(0))


def main(argv):
    if len(argv) != 2:
        sys.exit(__doc__)
    root = argv[1]
    pages = sorted(glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True))
    pages.append(os.path.join(root, "README.md"))
    bad = 0
    for page in pages:
        rel = os.path.relpath(page, root)
        with open(page, encoding="utf-8") as f:
            text = f.read()
        for p in problems(rel, text):
            print("not ok - " + p)
            bad += 1
    perf = os.path.join(root, "docs", "performance.md")
    with open(perf, encoding="utf-8") as f:
        lines = f.read().count("\n")
    if lines > MAX_PERFORMANCE_LINES:
        print("not ok - docs/performance.md has %d lines (at most %d)" % (lines, MAX_PERFORMANCE_LINES))
        bad += 1
    print("%s - %d pages state the present; docs/performance.md %d lines" %
          ("ok" if not bad else "not ok", len(pages), lines))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
