#!/usr/bin/env python3
"""A small gear as ASCII STL: geargen.py OUT. 12 trapezoid teeth (root radius 8,
tip 10) round a 24-sided bore of radius 3, 2 thick, caps zipped by angle."""
import math, sys
# a gear: 12 teeth (trapezoids on a disc of 48 segments), a bore, 2 thick
out = sys.argv[1]
N, r0, r1, rb, H = 12, 8.0, 10.0, 3.0, 2.0
outer = []
for t in range(N):
    a = 2 * math.pi * t / N
    da = 2 * math.pi / N
    for f, r in ((0.0, r0), (0.25, r0), (0.35, r1), (0.65, r1), (0.75, r0)):
        outer.append((r * math.cos(a + f * da), r * math.sin(a + f * da)))
bore = [(rb * math.cos(2 * math.pi * i / 24), rb * math.sin(2 * math.pi * i / 24)) for i in range(24)]
tris = []
def wall(loop, inward):
    n = len(loop)
    for i in range(n):
        (x0, y0), (x1, y1) = loop[i], loop[(i + 1) % n]
        a, b, c, d = (x0, y0, 0), (x1, y1, 0), (x1, y1, H), (x0, y0, H)
        if inward: tris.extend([(a, c, b), (a, d, c)])
        else: tris.extend([(a, b, c), (a, c, d)])
wall(outer, False)
wall(bore, True)
# caps: the ring between the bore and the teeth, by a fan over matched angles
def cap(z, up):
    # triangulate the annulus: each outer vertex to its nearest-angle bore vertex
    no, nb = len(outer), len(bore)
    ang = lambda p: math.atan2(p[1], p[0]) % (2 * math.pi)
    pts = sorted([(ang(p), 0, i) for i, p in enumerate(outer)] + [(ang(p), 1, i) for i, p in enumerate(bore)])
    # merge the two loops by angle (a zipper)
    io = ib = 0
    # find starting indices at angle 0
    so = min(range(no), key=lambda i: ang(outer[i])); sb = min(range(nb), key=lambda i: ang(bore[i]))
    i = j = 0
    while i < no or j < nb:
        o0, o1 = outer[(so + i) % no], outer[(so + i + 1) % no]
        b0, b1 = bore[(sb + j) % nb], bore[(sb + j + 1) % nb]
        ao = ang(o1) if i + 1 < no else 2 * math.pi + ang(o1)
        ab = ang(b1) if j + 1 < nb else 2 * math.pi + ang(b1)
        if ao < 1e-9: ao += 2 * math.pi
        if ab < 1e-9: ab += 2 * math.pi
        if j >= nb or (i < no and ao <= ab):
            t = ((o0[0], o0[1], z), (o1[0], o1[1], z), (b0[0], b0[1], z)); i += 1
        else:
            t = ((o0[0], o0[1], z), (b1[0], b1[1], z), (b0[0], b0[1], z)); j += 1
        tris.append(t if up else (t[0], t[2], t[1]))
cap(H, True)
cap(0, False)
with open(out, "w") as f:
    f.write("solid gear\n")
    for t in tris:
        f.write("facet normal 0 0 0\nouter loop\n")
        for p in t: f.write("vertex %.9f %.9f %.9f\n" % p)
        f.write("endloop\nendfacet\n")
    f.write("endsolid gear\n")
