#!/usr/bin/env python3
"""The test's own reading of `lamina slice --html` pages.
  viewercheck.py json FILE.html   the embedded run (Python's JSON parser): one line a
                                  layer, "INDEX AREA SOLIDS HOLES PARENTS_OK", then
                                  "deposits N" (vectors of kind deposit)
  viewercheck.py grid Z W H       points of a W x H screenshot of the stepped ring
                                  (tests/models/viewer/stepped.ug) at height Z and what
                                  each must show: "X,Y tint" or "X,Y background", from
                                  the part's own geometry (point in polygon, even-odd)
                                  and the viewer's documented layout (core/out/viewer.html:
                                  a 40 px bar above, 28 px below, the run's extent
                                  fitted with a 20 px margin, centred, v up). Points
                                  within 6 px of an edge, or by the scale bar, are left out."""
import json
import re
import sys


def run_of(path):
    s = open(path, encoding="utf-8").read()
    m = re.search(r'<script type="application/json" id="lamina-run">(.*?)</script>', s, re.S)
    return json.loads(m.group(1))


def inside(poly, x, y):
    """ray casting: is (x, y) inside the polygon?"""
    c = False
    for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]):
        if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
            c = not c
    return c


def seg_dist(x, y, a, b):
    (x0, y0), (x1, y1) = a, b
    dx, dy = x1 - x0, y1 - y0
    t = max(0, min(1, ((x - x0) * dx + (y - y0) * dy) / (dx * dx + dy * dy)))
    return ((x0 + t * dx - x) ** 2 + (y0 + t * dy - y) ** 2) ** 0.5


def square(h):
    return [(-h, -h), (h, -h), (h, h), (-h, h)]


if sys.argv[1] == "json":
    run = run_of(sys.argv[2])
    assert run["format"] == "lamina-run" and run["version"] == 1
    for L in run["layers"]:
        ids = {c["id"]: c for c in L["contours"]}
        solids = sum(1 for c in L["contours"] if c["solid"])
        # a hole's parent is a solid around it, a top-level contour has none
        parents = all((c["parent"] is None) == (c["depth"] == 0) and
                      (c["parent"] is None or ids[c["parent"]]["solid"] != c["solid"]) for c in L["contours"])
        print(L["index"], "%.6g" % L["stats"]["area"], solids, len(L["contours"]) - solids, parents)
    print("deposits", sum(1 for L in run["layers"] for v in L["vectors"] if v["kind"] == "deposit"))
elif sys.argv[1] == "grid":
    z, W, H = float(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4])
    # the part: rings around a 2 x 2 hole, 6 x 6 below z = 1, 4 x 4 above
    polys = [square(3 if z < 1 else 2), square(1)]
    box = (-3, -3, 3, 3)                       # the run's extent in x, y
    top, ch = 40, H - 40 - 28                  # the drawing
    s = min((W - 40) / (box[2] - box[0]), (ch - 40) / (box[3] - box[1]))
    cu, cv = (box[0] + box[2]) / 2, (box[1] + box[3]) / 2
    for i in range(-16, 17):
        for j in range(-16, 17):
            u, v = i * 0.22, j * 0.22
            x, y = W / 2 + (u - cu) * s, top + ch / 2 - (v - cv) * s
            if not (0 <= x < W and top <= y < top + ch):
                continue
            if x < 200 and y > top + ch - 36:  # the scale bar
                continue
            near = min(seg_dist(u, v, a, b) for p in polys for a, b in zip(p, p[1:] + p[:1]))
            if near * s < 6:
                continue
            material = sum(inside(p, u, v) for p in polys) % 2 == 1
            print("%d,%d %s" % (round(x), round(y), "tint" if material else "background"))
