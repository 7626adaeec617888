#!/usr/bin/env python3
"""The axes of grano's figures fit their data. Each gnuplot script given
(the .gp saved beside every figure) is replayed by gnuplot on a null
terminal; after each plot command gnuplot reports the range its axes took
(GPVAL_X_MIN...) and the range of the data drawn (GPVAL_DATA_X_MIN...). An
axis more than five times wider than its data (in decades on a log axis)
is the fault: the data squeezed into a corner. Data within a thousandth
of their magnitude (a thousandth of a decade on a log axis) are one value,
not checked. TAP.

usage: figure_axes.py SCRIPT.gp ...     (or directories holding .gp files)
"""
import math
import os
import re
import subprocess
import sys

WIDER = 5.0
REPORT = ('print sprintf("AXES %s %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g", "{logs}", '
          'GPVAL_X_MIN, GPVAL_X_MAX, GPVAL_DATA_X_MIN, GPVAL_DATA_X_MAX, '
          'GPVAL_Y_MIN, GPVAL_Y_MAX, GPVAL_DATA_Y_MIN, GPVAL_DATA_Y_MAX)')


def log_change(s, logs):
    """The x and y log flags after statement s (gnuplot keeps no variable
    for them: GPVAL_X_LOG is the base, set or not)."""
    m = re.match(r'(set|unset)\s+log(?:scale)?\b\s*([a-z0-9]*)', s)
    if not m:
        return logs
    axes = m.group(2) or 'xyzcbx2y2'
    on = m.group(1) == 'set'
    return [on if 'x' in axes.replace('x2', '') else logs[0],
            on if 'y' in axes.replace('y2', '') else logs[1]]


def instrument(text):
    """The script on the null terminal with a report after each plot."""
    out, cont, logs = [], False, [False, False]
    for line in text.splitlines():
        s = line.strip()
        if re.match(r'set\s+(term|terminal|output)\b', s):
            continue
        for stmt in s.split(';'):
            logs = log_change(stmt.strip(), logs)
        out.append(line)
        if (re.match(r'plot\b', s) or cont):
            cont = s.endswith('\\')
            if not cont:
                out.append(REPORT.replace('{logs}', '%d%d' % tuple(logs)))
    return 'set terminal unknown\n' + '\n'.join(out) + '\n'


def span(lo, hi, log):
    if log:
        if lo <= 0 or hi <= 0:
            return float('nan')
        return math.log10(hi / lo)
    return hi - lo


def check(path):
    """(ok, message) for each plot of the script."""
    text = open(path, encoding='utf-8').read()
    r = subprocess.run(['gnuplot'], input=instrument(text), capture_output=True, text=True,
                       cwd=os.path.dirname(os.path.abspath(path)), timeout=60)
    rows = [l.split() for l in (r.stdout + r.stderr).splitlines() if l.startswith('AXES ')]
    if r.returncode or not rows:
        return [(False, '%s: gnuplot failed to replay it: %s' % (path, r.stderr.strip()[-300:]))]
    res = []
    for k, row in enumerate(rows):
        logs, v = row[1], [float(x) for x in row[2:]]
        for a, (lo, hi, dlo, dhi) in enumerate((v[0:4], v[4:8])):
            log = logs[a] == '1'
            ds, axs = span(dlo, dhi, log), span(lo, hi, log)
            name = '%s plot %d, %s axis%s' % (os.path.basename(path), k + 1, 'xy'[a], ' (log)' if log else '')
            one = (log and ds < 1e-3) or (not log and ds <= 1e-3 * max(abs(dlo), abs(dhi)))
            if not (ds > 0) or not math.isfinite(ds) or abs(dlo) > 1e300 or one:
                res.append((True, '%s: no data or one value, not checked' % name))
                continue
            ratio = axs / ds
            res.append((ratio <= WIDER, '%s: axis %.4g..%.4g, data %.4g..%.4g, %.2f times wider'
                        % (name, lo, hi, dlo, dhi, ratio)))
    return res


def main(args):
    paths = []
    for a in args:
        if os.path.isdir(a):
            paths += sorted(os.path.join(a, f) for f in os.listdir(a) if f.endswith('.gp'))
        else:
            paths.append(a)
    if not paths:
        print('1..0 # SKIP no figure scripts given')
        return 0
    results = [r for p in paths for r in check(p)]
    print('1..%d' % len(results))
    bad = 0
    for i, (ok, msg) in enumerate(results, 1):
        print('%s %d - %s' % ('ok' if ok else 'not ok', i, msg))
        bad += not ok
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
