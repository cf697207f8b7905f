#!/usr/bin/env python3
"""A comb for make bench: N separate boxes in a row (0.5 x 20 x 10, one
unit apart), written as a binary STL. Every layer of it holds N contours
side by side, all spanning the same heights: the case where classifying
contours by testing each against every edge around it goes quadratic.
usage: comb.py N OUT.stl"""
import struct
import sys

n, out = int(sys.argv[1]), sys.argv[2]
# corners: bit 0 x, bit 1 y, bit 2 z; faces as outward quads
quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (1, 3, 7, 5), (0, 4, 6, 2)]
with open(out, "wb") as f:
    f.write(b"comb".ljust(80, b" "))
    f.write(struct.pack("<I", 12 * n))
    for i in range(n):
        x0, x1 = float(i), i + 0.5
        c = [(x1 if k & 1 else x0, 20.0 if k & 2 else 0.0, 10.0 if k & 4 else 0.0) for k in range(8)]
        for a, b, cc, d in quads:
            for tri in ((a, b, cc), (a, cc, d)):
                f.write(struct.pack("<3f", 0.0, 0.0, 0.0))
                for k in tri:
                    f.write(struct.pack("<3f", *c[k]))
                f.write(b"\0\0")
