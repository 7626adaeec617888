"""TAP output for the experiment tests written in Python."""
import sys


class Tap:
    def __init__(self):
        self.n = 0
        self.fails = 0

    def check(self, ok, what, detail=""):
        self.n += 1
        # a message of several lines (a refusal naming several features):
        # its lines after the first are comments
        print("%s %d - %s" % ("ok" if ok else "not ok", self.n, str(what).replace("\n", "\n# ")))
        if not ok:
            self.fails += 1
            print("# " + str(detail).replace("\n", "\n# "))

    def finish(self):
        print("1..%d" % self.n)
        return 1 if self.fails else 0


def skip(why):
    print("1..0 # SKIP " + why)
    sys.exit(0)
