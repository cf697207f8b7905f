#!/usr/bin/env python3
"""Small test meshes as ASCII STL: meshgen.py sphere|torus|thinwall OUT"""
import math
import sys

def stl(tris, out):
    with open(out, "w") as f:
        f.write("solid t\n")
        for a, b, c in tris:
            f.write("facet normal 0 0 0\nouter loop\n")
            for p in (a, b, c):
                f.write("vertex %.9f %.9f %.9f\n" % p)
            f.write("endloop\nendfacet\n")
        f.write("endsolid t\n")

def grid(fn, nu, nv, closed_v):
    """quads of a parametric surface fn(i, j), outward by the (u, v) order"""
    tris = []
    for i in range(nu):
        for j in range(nv):
            a, b = fn(i, j), fn(i + 1, j)
            c, d = fn(i + 1, j + 1), fn(i, j + 1)
            if a != b and a != c and b != c:
                tris.append((a, b, c))
            if a != c and a != d and c != d:
                tris.append((a, c, d))
    return tris

kind, out = sys.argv[1], sys.argv[2]
if kind == "sphere":
    R, nu, nv = 4.0, 48, 24
    def p(i, j):
        th = 2 * math.pi * (i % nu) / nu
        ph = -math.pi / 2 + math.pi * j / nv
        if j == 0:
            return (0.0, 0.0, -R)
        if j == nv:
            return (0.0, 0.0, R)
        return (R * math.cos(ph) * math.cos(th), R * math.cos(ph) * math.sin(th), R * math.sin(ph))
    stl(grid(p, nu, nv, False), out)
elif kind == "torus":
    R, r, nu, nv = 4.0, 1.5, 48, 24
    def p(i, j):
        th = 2 * math.pi * (i % nu) / nu
        ph = 2 * math.pi * (j % nv) / nv
        return ((R + r * math.cos(ph)) * math.cos(th), (R + r * math.cos(ph)) * math.sin(th), r * math.sin(ph))
    stl(grid(p, nu, nv, True), out)
elif kind == "thinwall":
    # a square tube 10 wide with 0.3 walls, 3 high (a ring extruded)
    O = [(0, 0), (10, 0), (10, 10), (0, 10)]
    I = [(0.3, 0.3), (9.7, 0.3), (9.7, 9.7), (0.3, 9.7)]
    z0, z1 = 0.0, 3.0
    t = []
    def quad(a, b, c, d):
        t.extend([(a, b, c), (a, c, d)])
    for k in range(4):
        o0, o1, i0, i1 = O[k], O[(k + 1) % 4], I[k], I[(k + 1) % 4]
        quad(o0 + (z0,), o1 + (z0,), o1 + (z1,), o0 + (z1,))      # outer wall
        quad(i1 + (z0,), i0 + (z0,), i0 + (z1,), i1 + (z1,))      # inner wall
        quad(o0 + (z1,), o1 + (z1,), i1 + (z1,), i0 + (z1,))      # top
        quad(i0 + (z0,), i1 + (z0,), o1 + (z0,), o0 + (z0,))      # bottom
    stl(t, out)
