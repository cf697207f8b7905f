#!/usr/bin/env python3
"""Models for the support tests (supports.t), as ASCII STL:
supportgen.py MODEL OUT, MODEL one of
  tee      a T: a stem 5 wide, 10 high, a bar 20 x 8 x 4 on it (one shell:
           the T profile in x-z extruded along y)
  arch     a bridge 20 x 8 x 10: a box with an arched opening (12 wide, the
           springing at z = 2, a semicircle of radius 6 above it)
  sphere   a UV sphere of radius 8 (its lower half overhangs the plate)
  bracket  a block 20 x 10 x 16 with a horizontal hole of radius 4 along y
           through it, its axis at z = 8 (the hole's crown is an overhang)
  float    two shells: a box 10 x 10 x 6 on the plate and a slab 15 x 8 x 2
           at z = 9..11, over the box and sticking out 7 beyond it
  cube     a 10 mm cube (stands by itself along z)
Every shell is closed and outward-facing."""
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

def area2(poly):
    return sum(poly[i][0] * poly[(i + 1) % len(poly)][1] - poly[(i + 1) % len(poly)][0] * poly[i][1]
               for i in range(len(poly)))

def ears(poly):
    """triangles of the simple CCW polygon poly (ear clipping), as index triples"""
    idx = list(range(len(poly)))
    tris = []
    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    while len(idx) > 3:
        n = len(idx)
        for k in range(n):
            i, j, l = idx[k - 1], idx[k], idx[(k + 1) % n]
            a, b, c = poly[i], poly[j], poly[l]
            if cross(a, b, c) <= 1e-12:
                continue
            inside = False
            for m in idx:
                if m in (i, j, l):
                    continue
                p = poly[m]
                if cross(a, b, p) >= 0 and cross(b, c, p) >= 0 and cross(c, a, p) >= 0:
                    inside = True
                    break
            if not inside:
                tris.append((i, j, l))
                idx.pop(k)
                break
        else:
            raise SystemExit("supportgen: no ear found")
    tris.append(tuple(idx))
    return tris

def extrude_y(rings, caps, y0, y1):
    """a solid from profiles in the x-z plane extruded from y = y0 to y1.
    rings: the boundary loops, each CCW seen in the (x, z) plane for the
    outer boundary and CW for holes (material on the left); caps: triangles
    of the profile's area as point triples (x, z), CCW in (x, z)."""
    tris = []
    P = lambda q, y: (q[0], y, q[1])
    # (x, z) CCW seen with y pointing away: the outward normal of the y = y0
    # cap is -y, and x cross z = -y, so CCW (x, z) triangles face -y there
    for a, b, c in caps:
        tris.append((P(a, y0), P(b, y0), P(c, y0)))
        tris.append((P(a, y1), P(c, y1), P(b, y1)))
    for ring in rings:
        n = len(ring)
        for i in range(n):
            a, b = ring[i], ring[(i + 1) % n]
            # material on the left of a->b in (x, z): the outward normal is
            # to the right, (dz, -dx) in (x, z)
            tris.append((P(a, y0), P(a, y1), P(b, y1)))
            tris.append((P(a, y0), P(b, y1), P(b, y0)))
    return tris

def profile(poly, y0, y1):
    if area2(poly) < 0:
        poly = poly[::-1]
    caps = [(poly[i], poly[j], poly[k]) for i, j, k in ears(poly)]
    return extrude_y([poly], caps, y0, y1)

def box(x0, y0, z0, x1, y1, z1):
    return profile([(x0, z0), (x1, z0), (x1, z1), (x0, z1)], y0, y1)

def tee():
    return profile([(-2.5, 0), (2.5, 0), (2.5, 10), (10, 10), (10, 14), (-10, 14), (-10, 10), (-2.5, 10)], -4, 4)

def arch():
    poly = [(-10, 0), (-6, 0), (-6, 2)]
    n = 32
    for i in range(1, n):  # the opening's semicircle, from x = -6 over the crown to x = 6
        t = math.pi - math.pi * i / n
        poly.append((6 * math.cos(t), 2 + 6 * math.sin(t)))
    poly += [(6, 2), (6, 0), (10, 0), (10, 10), (-10, 10)]
    return profile(poly, -4, 4)

def sphere(R=8.0, nu=24, nv=48):
    def p(i, j):
        th = math.pi * i / nu  # from the top pole
        ph = 2 * math.pi * j / nv
        if i == 0:
            return (0.0, 0.0, R)
        if i == nu:
            return (0.0, 0.0, -R)
        return (R * math.sin(th) * math.cos(ph), R * math.sin(th) * math.sin(ph), R * math.cos(th))
    tris = []
    for i in range(nu):
        for j in range(nv):
            a, b, c, d = p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)
            if i > 0:
                tris.append((a, b, d))
            if i < nu - 1:
                tris.append((b, c, d))
    return tris

def bracket():
    # outer rectangle x in [-10, 10], z in [0, 16]; the hole: radius 4
    # around (0, 8). The cap between them by rays from the centre (the
    # rectangle is star-shaped from it): every ray's circle point and
    # rectangle point, the corners among the rays.
    cx, cz, r = 0.0, 8.0, 4.0
    corners = [(10, 0), (10, 16), (-10, 16), (-10, 0)]
    angs = [2 * math.pi * i / 48 for i in range(48)]
    angs += [math.atan2(z - cz, x - cx) % (2 * math.pi) for x, z in corners]
    angs = sorted(set(round(a, 12) for a in angs))
    def hit(a):
        dx, dz = math.cos(a), math.sin(a)
        ts = []
        if dx > 1e-12: ts.append((10 - cx) / dx)
        if dx < -1e-12: ts.append((-10 - cx) / dx)
        if dz > 1e-12: ts.append((16 - cz) / dz)
        if dz < -1e-12: ts.append((0 - cz) / dz)
        t = min(ts)
        return (cx + t * dx, cz + t * dz)
    outer = [hit(a) for a in angs]
    inner = [(cx + r * math.cos(a), cz + r * math.sin(a)) for a in angs]
    caps = []
    n = len(angs)
    for i in range(n):
        j = (i + 1) % n
        caps.append((inner[i], outer[i], outer[j]))
        caps.append((inner[i], outer[j], inner[j]))
    return extrude_y([outer, inner[::-1]], caps, -5, 5)

def floating():
    return box(-5, -5, 0, 5, 5, 6) + box(-3, -4, 9, 12, 4, 11)

def cube():
    return box(0, 0, 0, 10, 10, 10)

MODELS = {"tee": tee, "arch": arch, "sphere": sphere, "bracket": bracket, "float": floating, "cube": cube}

if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in MODELS:
        sys.exit("usage: supportgen.py %s OUT" % "|".join(MODELS))
    stl(MODELS[sys.argv[1]](), sys.argv[2])
