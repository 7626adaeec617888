#!/usr/bin/python3
"""The command line's habits (issue 19): every subcommand has --help (exit
0, usage on stdout) and --version; --name=VALUE and --name VALUE both work;
bad numbers are refused naming the flag; writers refuse to replace a result
without --force. TAP output. Usage: cli_habits.py GRANO"""
import os
import subprocess
import sys
import tempfile

GRANO = sys.argv[1]
COMMANDS = ["run", "info", "methods", "bench", "bench dem", "bench cd", "bench edmd", "silo-start",
            "silo-flow", "course", "compare"]
SCENE = "[domain]\nwidth = 10\nheight = 10\n[species]\ncount = 20\n[init]\nkind = random\n[run]\nuntil = 0.01\n"


def grano(args, cwd):
    p = subprocess.run([GRANO] + args, cwd=cwd, capture_output=True, text=True, errors="replace", timeout=120)
    return p.returncode, p.stdout, p.stderr


def main():
    checks = []
    with tempfile.TemporaryDirectory() as tmp:
        for c in COMMANDS:
            rc, out, err = grano(c.split() + ["--help"], tmp)
            checks.append(("%s --help: exit 0, usage on stdout" % c, rc == 0 and "usage" in out, err))
            rc, out, err = grano(c.split() + ["--version"], tmp)
            checks.append(("%s --version: exit 0, prints the version" % c, rc == 0 and out.startswith("grano"), err))
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
