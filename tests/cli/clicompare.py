#!/usr/bin/env python3
"""clicompare.py A B: the same CLI ASCII commands, numbers equal within 2e-5
(a binary file decoded by clidecode.py holds float32)."""
import re
import sys

a, b = (open(f).read().split("\n") for f in sys.argv[1:3])
num = re.compile(r"-?\d+\.\d+")
bad = len(a) != len(b)
for x, y in zip(a, b):
    if num.sub("#", x) != num.sub("#", y) or any(
            abs(float(p) - float(q)) > 2e-5 for p, q in zip(num.findall(x), num.findall(y))):
        print("differ: %s / %s" % (x[:80], y[:80]))
        bad = True
        break
sys.exit(1 if bad else 0)
