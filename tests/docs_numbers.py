#!/usr/bin/env python3
"""The docs' numbers are the program's numbers. A fenced block of a doc
with the info string `numbers` (or `numbers slow`) holds a command and
lines of its output ("..." for lines left out), each quoted figure written
{VALUE ± BAR}:

    ```numbers
    $ grano course cooling --quick
      largest deviation: {1.77 ± 0.8} % from the law in C/N, ...
    ```

This reruns each command (in a fresh folder, `grano` being the build's)
and finds, for each line, an output line of the same text (blanks aside)
whose figures lie within their bars. The bars are the spread over seeds
(`--spread K` prints, for each figure, its value and its standard
deviation over seeds 1..K, to set them). Blocks marked `slow` run only
with --slow. TAP.

usage: docs_numbers.py GRANO SOURCE_ROOT [--slow] [--spread K]
"""
import glob
import os
import re
import shlex
import statistics
import subprocess
import sys
import tempfile
import time

FIG = re.compile(r'\{\s*([-+]?[0-9.]+(?:[eE][-+]?\d+)?)\s*±\s*([0-9.]+(?:[eE][-+]?\d+)?)\s*\}')
NUM = r'([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|inf|nan)'


def blocks(root):
    """(doc, line, slow, command, [(template line, [(value, bar)])])."""
    for path in sorted(glob.glob(os.path.join(root, 'docs', '**', '*.md'), recursive=True)):
        lines = open(path, encoding='utf-8').read().splitlines()
        i = 0
        while i < len(lines):
            m = re.match(r'\s*```numbers(\s+slow)?\s*$', lines[i])
            if not m:
                i += 1
                continue
            start, i = i + 1, i + 1
            body = []
            while i < len(lines) and not lines[i].strip().startswith('```'):
                body.append(lines[i])
                i += 1
            cmd = body[0].strip()
            assert cmd.startswith('$ grano '), '%s:%d: a numbers block starts with "$ grano"' % (path, start + 1)
            checks = [(l, [(float(a), float(b)) for a, b in FIG.findall(l)]) for l in body[1:]
                      if l.strip() and l.strip() != '...']
            yield os.path.relpath(path, root), start, bool(m.group(1)), cmd[2:], checks


def pattern(line):
    """The template line as a regex: its text, any run of blanks, each
    figure a number."""
    parts = FIG.split(line.strip())
    out = []
    for k in range(0, len(parts), 3):
        text = re.escape(parts[k])
        out.append(re.sub(r'(\\ )+', r'\\s+', text))
        if k + 1 < len(parts):
            out.append(NUM)
    return re.compile(''.join(out))


def run(grano, cmd, seed=None):
    args = shlex.split(cmd)
    args[0] = grano
    if seed is not None:
        args += ['--seed', str(seed)]
    with tempfile.TemporaryDirectory() as d:
        t0 = time.time()
        r = subprocess.run(args, cwd=d, capture_output=True, text=True, timeout=900)
        return r.returncode, r.stdout, r.stderr, time.time() - t0


def figures(out, tmpl):
    pat = pattern(tmpl)
    found = [m for m in (pat.search(l) for l in out.splitlines()) if m]
    return found


def check(grano, doc, line, cmd, checks):
    rc, out, err, wall = run(grano, cmd)
    res = []
    if rc:
        return [(False, '%s:%d: `%s` exited %d: %s' % (doc, line, cmd, rc, err.strip()[-300:]))]
    for tmpl, want in checks:
        found = figures(out, tmpl)
        if not found:
            res.append((False, '%s:%d: no line of `%s` reads like "%s"' % (doc, line, cmd, tmpl.strip())))
            continue
        best = None
        for m in found:
            got = [float(x) for x in m.groups()]
            bad = [(g, v, b) for g, (v, b) in zip(got, want) if not abs(g - v) <= b]
            if not bad:
                best = None
                break
            best = bad
        if best:
            res.append((False, '%s:%d: `%s`: %s' % (doc, line, cmd, ', '.join(
                '%g where the doc says %g ± %g' % x for x in best))))
        else:
            res.append((True, '%s:%d: `%s` %.1f s: "%s"' % (doc, line, cmd, wall, tmpl.strip()[:60])))
    return res


def spread(grano, doc, line, cmd, checks, k):
    per = {}
    for s in range(1, k + 1):
        rc, out, err, wall = run(grano, cmd, s)
        for j, (tmpl, _) in enumerate(checks):
            f = figures(out, tmpl)
            if f:
                per.setdefault(j, []).append([float(x) for x in f[0].groups()])
    print('%s:%d: %s' % (doc, line, cmd))
    for j, (tmpl, want) in enumerate(checks):
        rows = per.get(j, [])
        if len(rows) < 2:
            print('   (not found) %s' % tmpl.strip())
            continue
        cols = list(zip(*rows))
        print('   %s' % tmpl.strip())
        print('      seed 1: %s' % ', '.join('%.6g' % c[0] for c in cols))
        print('      sd over %d seeds: %s' % (len(rows), ', '.join('%.3g' % statistics.stdev(c) for c in cols)))


def main(argv):
    grano, root = argv[1], argv[2]
    slow = '--slow' in argv
    k = int(argv[argv.index('--spread') + 1]) if '--spread' in argv else 0
    todo = [b for b in blocks(root) if slow or not b[2]]
    if k:
        for doc, line, _, cmd, checks in todo:
            spread(grano, doc, line, cmd, checks, k)
        return 0
    results = []
    for doc, line, _, cmd, checks in todo:
        results += check(grano, doc, line, cmd, checks)
    print('1..%d' % len(results))
    for i, (ok, msg) in enumerate(results, 1):
        print('%s %d - %s' % ('ok' if ok else 'not ok', i, msg))
    return 0 if all(ok for ok, _ in results) else 1


if __name__ == '__main__':
    sys.exit(main(sys.argv))
