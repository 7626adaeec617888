#!/usr/bin/python3
"""The command line's habits: every subcommand (as grano --help lists them,
and bench for every method grano methods lists) has --help (exit 0, usage
on stdout) and --version; --name=VALUE and --name VALUE both work;
bad numbers are refused naming the flag; writers refuse to replace a result
without --force. TAP output. Usage: cli_habits.py GRANO"""
import os
import subprocess
import sys
import tempfile

GRANO = sys.argv[1]
SCENE = "[domain]\nwidth = 10\nheight = 10\n[species]\ncount = 20\n[init]\nkind = random\n[run]\nuntil = 0.01\n"


def grano(args, cwd):
    p = subprocess.run([GRANO] + args, cwd=cwd, capture_output=True, text=True, errors="replace", timeout=120)
    return p.returncode, p.stdout, p.stderr


def commands(tmp):
    """Every subcommand (grano --help) and every method's bench (the
    registry, through grano methods): none is named here."""
    rc, out, _ = grano(["--help"], tmp)
    subs = [line.split()[0] for line in out.split("commands:", 1)[-1].splitlines() if line.startswith("  ")]
    rc, out, _ = grano(["methods"], tmp)
    methods = [line.split(":")[0] for line in out.splitlines() if line and not line[0].isspace() and ": " in line]
    return subs, methods


def main():
    checks = []
    with tempfile.TemporaryDirectory() as tmp:
        subs, methods = commands(tmp)
        checks.append(("grano --help lists the subcommands, export among them (%d)" % len(subs),
                       "export" in subs and "run" in subs, ""))
        checks.append(("grano methods lists the methods (%d)" % len(methods), len(methods) >= 1, ""))
        for c in subs + ["bench " + m for m in methods] + ["bench --generic " + m for m in methods]:
            rc, out, err = grano(c.split() + ["--help"], tmp)
            checks.append(("%s --help: exit 0, usage on stdout" % c, rc == 0 and "usage" in out, err))
            rc, out, err = grano(c.split() + ["--version"], tmp)
            checks.append(("%s --version: exit 0, prints the version" % c, rc == 0 and out.startswith("grano"), err))
        # every registered method is benchable through the method interface
        for m in methods:
            rc, out, err = grano(["bench", "--generic", m, "--quick"], tmp)
            kv = dict(w.split("=", 1) for w in out.split() if "=" in w) if out.startswith("RESULT") else {}
            good = rc == 0 and kv.get("method") == m and int(kv.get("steps", 0)) > 0 and \
                float(kv.get("sim_time", 0)) >= 1 and float(kv.get("grain_steps_per_s", 0)) > 0
            checks.append(("bench --generic %s --quick: a RESULT line, steps > 0, simulated time 1 reached" % m,
                           good, err + out))
        with open(os.path.join(tmp, "s.ini"), "w") as f:
            f.write(SCENE)
        rc, out, err = grano(["run", "s.ini", "--out=a.h5", "-q"], tmp)
        checks.append(("run --out=FILE", rc == 0 and os.path.exists(os.path.join(tmp, "a.h5")), err))
        rc, out, err = grano(["run", "s.ini", "--out", "b.h5", "-q"], tmp)
        checks.append(("run --out FILE", rc == 0 and os.path.exists(os.path.join(tmp, "b.h5")), err))
        for args, flag in [(["run", "s.ini", "--seed", "abc"], "--seed"),
                           (["run", "s.ini", "--until=1e400"], "--until"),
                           (["course", "maxwell", "--seed=abc"], "--seed"),
                           (["course", "cooling", "--alpha", "1.5"], "--alpha"),
                           (["bench", "cd", "--steps", "ten"], "--steps"),
                           (["bench", "edmd", "--ratio", "0"], "--ratio"),
                           (["bench", "dem", "--threads", "2x"], "--threads"),
                           (["silo-flow", "--seed", "abc"], "--seed"),
                           (["info", "--bogus", "x.h5"], "--bogus")]:
            rc, out, err = grano(args, tmp)
            checks.append(("%s refused naming %s" % (" ".join(args), flag), rc == 2 and flag in err, err))
        # course refuses to replace an exercise's result without --force
        os.makedirs(os.path.join(tmp, "co"))
        with open(os.path.join(tmp, "co", "maxwell.h5"), "w") as f:
            f.write("precious")
        rc, out, err = grano(["course", "maxwell", "--quick", "--out", "co"], tmp)
        kept = open(os.path.join(tmp, "co", "maxwell.h5")).read() == "precious"
        checks.append(("course without --force keeps an existing result", rc == 2 and "--force" in err and kept, err))
    for i, (name, good, why) in enumerate(checks, 1):
        print("%s %d - %s" % ("ok" if good else "not ok", i, name))
        if not good and why:
            print("# " + why.strip().replace("\n", "\n# "))
    print("1..%d" % len(checks))
    return 0 if all(c[1] for c in checks) else 1


if __name__ == "__main__":
    sys.exit(main())
