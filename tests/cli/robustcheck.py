#!/usr/bin/env python3
"""Sanity of SLS runs written with --json (hatch_robust.t), by the test's own
geometry (nothing from lamina or GEOS):

usage: robustcheck.py STL WIDTH RUN.json...

For each run: the layer count is the one uniform layers of WIDTH from the
STL's lowest vertex give (ceil of its height / WIDTH), layer i (from 1) is
present once, in order, cut in its middle (z = zmin + (i - 1/2) WIDTH); and
every hatch vector (kind core, upskin or downskin) lies in its layer's
region: points at 1/4, 1/2 and 3/4 of it are inside the contours by the
even-odd rule, or within TOL of one of their edges. Prints one line per
failed run (the first few problems) and exits 1 if any failed."""
import json
import math
import sys

TOL = 1e-6
HATCH = ("core", "upskin", "downskin")


def stl_z(path):
    lo, hi = math.inf, -math.inf
    for line in open(path):
        f = line.split()
        if f and f[0] == "vertex":
            z = float(f[3])
            lo, hi = min(lo, z), max(hi, z)
    return lo, hi


class Region:
    """a layer's contours: even-odd inside test and distance to the edges,
    with the edges bucketed by rows of v for speed"""

    def __init__(self, loops, row=0.25):
        self.row = row
        self.rows = {}
        for L in loops:
            n = len(L)
            for i in range(n):
                a, b = L[i], L[(i + 1) % n]
                e = (a[0], a[1], b[0], b[1])
                for r in range(math.floor(min(a[1], b[1]) / row) - 1, math.floor(max(a[1], b[1]) / row) + 2):
                    self.rows.setdefault(r, []).append(e)

    def edges_near(self, y):
        return self.rows.get(math.floor(y / self.row), [])

    def inside(self, x, y):
        c = False
        seen = set()
        for e in self.edges_near(y):
            if e in seen:
                continue
            seen.add(e)
            x0, y0, x1, y1 = e
            if (y0 > y) != (y1 > y) and x0 + (y - y0) * (x1 - x0) / (y1 - y0) > x:
                c = not c
        return c

    def near_edge(self, x, y):
        for x0, y0, x1, y1 in self.edges_near(y):
            dx, dy = x1 - x0, y1 - y0
            L2 = dx * dx + dy * dy
            t = 0 if L2 == 0 else max(0, min(1, ((x - x0) * dx + (y - y0) * dy) / L2))
            if math.hypot(x - x0 - t * dx, y - y0 - t * dy) <= TOL:
                return True
        return False


def check(run, zmin, zmax, width):
    d = json.load(open(run))
    want = math.ceil((zmax - zmin) / width - 1e-9)
    bad = []
    layers = d["layers"]
    if d["job"]["layers"] != want or len(layers) != want:
        bad.append("%d layers (job says %d), want %d" % (len(layers), d["job"]["layers"], want))
    for i, L in enumerate(layers):
        if L["index"] != i + 1:
            bad.append("layer %d has index %d" % (i + 1, L["index"]))
        if abs(L["z"] - (zmin + (i + 0.5) * width)) > 1e-6:
            bad.append("layer %d at z %.9g" % (i + 1, L["z"]))
        reg = Region([[p[:2] for p in c["points"]] for c in L["contours"] if c.get("region") is None])  # the section's
        for v in L["vectors"]:
            if v["kind"] not in HATCH:
                continue
            (x0, y0, _), (x1, y1, _) = v["from"], v["to"]
            for t in (0.25, 0.5, 0.75):
                x, y = x0 + t * (x1 - x0), y0 + t * (y1 - y0)
                if not reg.inside(x, y) and not reg.near_edge(x, y):
                    bad.append("layer %d: %s vector %s-%s leaves the region" % (i + 1, v["kind"], v["from"], v["to"]))
                    break
        if len(bad) > 3:
            break
    return bad


def main():
    stl, width, runs = sys.argv[1], float(sys.argv[2]), sys.argv[3:]
    zmin, zmax = stl_z(stl)
    failed = 0
    for run in runs:
        bad = check(run, zmin, zmax, width)
        if bad:
            failed += 1
            print("%s: %s" % (run, "; ".join(bad[:3])))
    print("# %d of %d runs sane" % (len(runs) - failed, len(runs)))
    return 1 if failed else 0


sys.exit(main())
