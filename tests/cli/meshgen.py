#!/usr/bin/env python3
"""Small test meshes as ASCII STL: meshgen.py sphere|torus|thinwall OUT;
meshgen.py boxes|slots|text OUT SEED: parts of near-coincident edges
(hatch_robust.t), unions of closed convex prisms for --fill nonzero:
  boxes  a box and copies of it rotated, tilted and moved by 1e-10 to 1e-3;
  slots  a comb of bars with slots 1e-5 to 0.2 wide, bars a hair off
         square and their tops a hair apart in height;
  text   "LAMINA" in overlapping strokes, rotated, and a copy a hair off;
  tubes  eccentric tubes, tilted or not, a faceted hole (through, or a
         void inside) whose wall to the faceted outline thins to a hair, to
         the beam's inset or twice it (lpbf-cli's).
SEED picks the jitter (random.Random: the same part for the same seed)."""
import math
import random
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

def prism(poly, z0, z1, tf):
    """closed prism over convex CCW polygon poly from z0 to z1, points mapped by tf"""
    b = [tf((x, y, z0)) for x, y in poly]
    t = [tf((x, y, z1)) for x, y in poly]
    n = len(poly)
    tris = []
    for i in range(1, n - 1):
        tris.append((b[0], b[i + 1], b[i]))
        tris.append((t[0], t[i], t[i + 1]))
    for i in range(n):
        j = (i + 1) % n
        tris.append((b[i], b[j], t[j]))
        tris.append((b[i], t[j], t[i]))
    return tris

def annulus(outer, inner, c):
    """triangles (CCW seen from +z) between convex CCW ring outer and CCW
    ring inner around point c inside both: the two rings walked together
    by angle about c"""
    def start(ring):
        ang = [math.atan2(p[1] - c[1], p[0] - c[0]) % (2 * math.pi) for p in ring]
        k = min(range(len(ring)), key=lambda i: ang[i])
        return ring[k:] + ring[:k], sorted(ang)
    (o, oa), (q, qa) = start(outer), start(inner)
    o, q, oa, qa = o + o[:1], q + q[:1], oa + [oa[0] + 2 * math.pi], qa + [qa[0] + 2 * math.pi]
    i = j = 0
    tris = []
    while i < len(o) - 1 or j < len(q) - 1:
        if j == len(q) - 1 or (i < len(o) - 1 and oa[i + 1] <= qa[j + 1]):
            tris.append((o[i], o[i + 1], q[j]))
            i += 1
        else:
            tris.append((o[i], q[j + 1], q[j]))
            j += 1
    return tris

def tube(outer, inner, c, z0, z1, tf):
    """a closed tube: prism over outer with a through hole over inner"""
    tris = []
    for a, b, d in annulus(outer, inner, c):
        tris.append((tf(a + (z1,)), tf(b + (z1,)), tf(d + (z1,))))
        tris.append((tf(a + (z0,)), tf(d + (z0,)), tf(b + (z0,))))
    for ring, out in ((outer, True), (inner, False)):
        n = len(ring)
        for i in range(n):
            a, b = ring[i], ring[(i + 1) % n]
            if not out:
                a, b = b, a
            tris.append((tf(a + (z0,)), tf(b + (z0,)), tf(b + (z1,))))
            tris.append((tf(a + (z0,)), tf(b + (z1,)), tf(a + (z1,))))
    return tris

def jig(center, turn=0.0, tilt=0.0, move=(0.0, 0.0, 0.0)):
    """rotate by turn about z and tilt about x through center, then move"""
    cz, sz, cx, sx = math.cos(turn), math.sin(turn), math.cos(tilt), math.sin(tilt)
    def tf(p):
        x, y, z = p[0] - center[0], p[1] - center[1], p[2] - center[2]
        x, y = cz * x - sz * y, sz * x + cz * y
        y, z = cx * y - sx * z, sx * y + cx * z
        return (x + center[0] + move[0], y + center[1] + move[1], z + center[2] + move[2])
    return tf

def rect(x0, y0, x1, y1):
    return [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]

def hair(rng):
    """a tiny signed amount, 1e-10 .. 1e-3"""
    return rng.choice((-1, 1)) * 10 ** rng.uniform(-10, -3)

def stroke(a, b, w):
    """a bar of width w from a to b, its ends grown by w/2 (joints overlap)"""
    dx, dy = b[0] - a[0], b[1] - a[1]
    L = math.hypot(dx, dy)
    ux, uy = dx / L, dy / L
    nx, ny = -uy * w / 2, ux * w / 2
    a = (a[0] - ux * w / 2, a[1] - uy * w / 2)
    b = (b[0] + ux * w / 2, b[1] + uy * w / 2)
    return [(a[0] - nx, a[1] - ny), (a[0] + nx, a[1] + ny), (b[0] + nx, b[1] + ny), (b[0] - nx, b[1] - ny)]

LETTERS = {
    "L": [((0, 6), (0, 0)), ((0, 0), (3, 0))],
    "A": [((0, 0), (1.5, 6)), ((1.5, 6), (3, 0)), ((0.75, 3), (2.25, 3))],
    "M": [((0, 0), (0, 6)), ((0, 6), (1.5, 3)), ((1.5, 3), (3, 6)), ((3, 6), (3, 0))],
    "I": [((1.5, 0), (1.5, 6))],
    "N": [((0, 0), (0, 6)), ((0, 6), (3, 0)), ((3, 0), (3, 6))],
}

def robust(kind, rng):
    tris = []
    if kind == "boxes":
        c = (5, 3, 1.5)
        tris += prism(rect(0, 0, 10, 6), 0, 3, jig(c))
        for _ in range(5):
            tris += prism(rect(0, 0, 10, 6), 0, 3 + hair(rng),
                          jig(c, hair(rng), hair(rng) / 10, (hair(rng), hair(rng), 0)))
        # a smaller block whose top is a hair off a layer's cut
        tris += prism(rect(2, 1, 8, 5), 0, 1.6 + hair(rng), jig(c, math.radians(30) + hair(rng)))
    elif kind == "slots":
        x = 0.0
        for g in (1e-5, 0.001, 0.01, 0.05, 0.081, 0.2, 1e-4):
            top = rng.choice((3.0, 2.0 + hair(rng), 2.8 + hair(rng)))
            tris += prism(rect(x, 0, x + 1, 8), 0, top, jig((x + 0.5, 4, 1), hair(rng) / 10, hair(rng) / 10))
            x += 1 + g
        # the back of the comb, its edge a hair off the bars' ends
        tris += prism(rect(-0.5, -1.5, x + 0.5, abs(hair(rng))), 0, 3, jig((x / 2, 0, 1)))
    elif kind == "text":
        turn = math.radians(13)
        for copy in range(2):
            off = (hair(rng), hair(rng), 0) if copy else (0, 0, 0)
            rot = turn + (hair(rng) if copy else 0)
            for k, ch in enumerate("LAMINA"):
                for a, b in LETTERS[ch]:
                    a, b = (a[0] + 4.2 * k, a[1]), (b[0] + 4.2 * k, b[1])
                    tris += prism(stroke(a, b, 0.7), 0, 2 if copy == 0 else 2 + hair(rng), jig((12, 3, 1), rot, 0, off))
    elif kind == "tubes":
        # eccentric tubes: a hole whose wall to the outline thins to a hair,
        # to the beam's inset or twice it, in other facets than the outline
        for k, gap in enumerate((abs(hair(rng)), 0.16 + hair(rng), 0.32 + hair(rng), 0.32 + abs(hair(rng)) * 100)):
            R, r, cx = 2.5, 1.5 + rng.uniform(0, 0.5), 6.0 * k
            n, m = rng.choice((48, 64, 90)), rng.choice((36, 50, 72))
            e = R - r - gap
            ph = rng.uniform(0, 2 * math.pi)
            tf = jig((cx, 0, 0.75), hair(rng), rng.choice((0.0, 0.05, hair(rng))))
            outer = [(cx + R * math.cos(2 * math.pi * i / n), R * math.sin(2 * math.pi * i / n)) for i in range(n)]
            inner = [(cx + e * math.cos(ph) + r * math.cos(2 * math.pi * i / m + 0.3),
                      e * math.sin(ph) + r * math.sin(2 * math.pi * i / m + 0.3)) for i in range(m)]
            if k % 2:
                tris += tube(outer, inner, (cx + e * math.cos(ph), e * math.sin(ph)), 0, 1.5, tf)
            else:
                # a void closed inside (its shell turned inward): the
                # layers below and above it are solid, its edges skins
                tris += prism(outer, 0, 1.5, tf)
                tris += [(a, c, b) for a, b, c in prism(inner, 0.35 + abs(hair(rng)), 1.15, tf)]
    else:
        raise SystemExit("meshgen.py: unknown part " + kind)
    return tris

kind, out = sys.argv[1], sys.argv[2]
if kind in ("boxes", "slots", "text", "tubes"):
    stl(robust(kind, random.Random(int(sys.argv[3]))), out)
    sys.exit(0)
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
