#!/usr/bin/env python3
"""The independent check of lamina's powder-bed supports (supports.t): its
own polygon code (even-odd point in polygon, point-to-segment distance,
edges bucketed in a uniform grid), the standard library only. Reads the
JSON of `lamina slice ... --json OUT --set frame=machine` (points in the
layer frame: u, v the plane, w the height).

  supportcheck.py stands JSON [--angle 45] [--tol T] [--step S]
      every point of part-plus-support of layer k >= 2 (a grid inside it,
      every contour vertex and edge midpoint nudged inside) lies in the
      part-or-support of layer k - 1 or within r_k + T of it, r_k =
      w_k tan(angle) (angle from the vertical); layer 1 is on the plate
  supportcheck.py vectors JSON [--teeth-layers N] [--gap-xy G] [--tol T]
      every point along every support vector: not inside its layer's part
      (beyond T) unless N > 0 and the part is absent there on some layer
      of the N below (a tooth); in its layer's support region (within T)
      unless a tooth; with G, at least G - T from the part of the layer
      (the support contours' edges too)
  supportcheck.py gapz JSON --layers N [--tol T]
      no support point (vectors, the support region's inside and outline)
      has part directly above it (beyond T) on any of the N layers above
  supportcheck.py none JSON
      no support contours, no support vectors
  supportcheck.py area JSON [--min A]
      prints every layer's support area (its own shoelace over the support
      contours, even-odd), to 0.01, one line; with A: fails when a support
      piece (a solid support contour less its holes) is below A
  supportcheck.py at JSON LAYER U V
      prints what layer LAYER (1-based) has at (U, V): part, support or
      nothing (a probe for the models' known places)
Failures are printed (layer, point, distance) and the exit status is 1;
the last line is a summary. Exit 2: a usage error or a JSON it cannot read."""
import argparse
import json
import math
import sys

INF = float("inf")


def seg_dist(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    L = dx * dx + dy * dy
    t = 0.0 if L == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / L))
    qx, qy = ax + t * dx - px, ay + t * dy - py
    return math.sqrt(qx * qx + qy * qy)


class Region:
    """a set of rings filled even-odd: edges in grid cells of side h (for
    distances) and in rows of height h (for the crossing count)"""

    def __init__(self, rings, h):
        self.rings = [r for r in rings if len(r) >= 3]
        self.h = h
        self.edges = []
        for r in self.rings:
            n = len(r)
            for i in range(n):
                a, b = r[i], r[(i + 1) % n]
                if a != b:
                    self.edges.append((a[0], a[1], b[0], b[1]))
        self.cells = {}
        self.rows = {}
        for e in self.edges:
            x0, x1 = min(e[0], e[2]), max(e[0], e[2])
            y0, y1 = min(e[1], e[3]), max(e[1], e[3])
            for j in range(math.floor(y0 / h), math.floor(y1 / h) + 1):
                self.rows.setdefault(j, []).append(e)
                for i in range(math.floor(x0 / h), math.floor(x1 / h) + 1):
                    self.cells.setdefault((i, j), []).append(e)
        if self.edges:
            xs = [e[0] for e in self.edges]
            ys = [e[1] for e in self.edges]
            self.bbox = (min(xs), min(ys), max(xs), max(ys))
        else:
            self.bbox = None

    def inside(self, x, y):
        c = False
        for ax, ay, bx, by in self.rows.get(math.floor(y / self.h), ()):
            if (ay > y) != (by > y):
                if ax + (y - ay) * (bx - ax) / (by - ay) > x:
                    c = not c
        return c

    def spans(self, y):
        """the region's intervals [x0, x1] on the line at height y (even-odd)"""
        xs = sorted(ax + (y - ay) * (bx - ax) / (by - ay)
                    for ax, ay, bx, by in self.rows.get(math.floor(y / self.h), ())
                    if (ay > y) != (by > y))
        return [(xs[i], xs[i + 1]) for i in range(0, len(xs) - 1, 2)]

    def bdist(self, x, y, d):
        """the distance to the boundary if below d (else d)"""
        h = self.h
        best = d
        for j in range(math.floor((y - d) / h), math.floor((y + d) / h) + 1):
            for i in range(math.floor((x - d) / h), math.floor((x + d) / h) + 1):
                for e in self.cells.get((i, j), ()):
                    ax, ay, bx, by = e
                    if (ax - x > best and bx - x > best) or (x - ax > best and x - bx > best) or \
                       (ay - y > best and by - y > best) or (y - ay > best and y - by > best):
                        continue
                    q = seg_dist(x, y, ax, ay, bx, by)
                    if q < best:
                        best = q
        return best

    def dist(self, x, y, d):
        """distance to the region (0 inside), exact below d"""
        if self.inside(x, y):
            return 0.0
        return self.bdist(x, y, d)

    def deep(self, x, y, tol):
        """inside, and farther than tol from the boundary"""
        return self.inside(x, y) and self.bdist(x, y, 2 * tol) > tol


class Layer:
    def __init__(self, L, h):
        self.index = L["index"]
        self.width = L["width"]
        part, sup, over = [], [], []
        for c in L["contours"]:  # the section's (no region), the support's, the overhang's
            ring = [(p[0], p[1]) for p in c["points"]]
            {None: part, "support": sup, "overhang": over}[c.get("region")].append(ring)
        self.part = Region(part, h)
        self.sup = Region(sup, h)
        self.over = Region(over, h)
        self.vectors = [v for v in L["vectors"] if v["kind"] == "support"]
        self.nsup = len(sup)

    def in_material(self, x, y):
        return self.part.inside(x, y) or self.sup.inside(x, y)

    def material_dist(self, x, y, d):
        if self.in_material(x, y):
            return 0.0
        return min(self.part.bdist(x, y, d), self.sup.bdist(x, y, d))


def die(msg):
    """a usage or input error: exit 2 (1 is a check that failed)"""
    print("supportcheck: %s" % msg, file=sys.stderr)
    sys.exit(2)


def load(path, h):
    with open(path) as f:
        d = json.load(f)
    job = d.get("job", {})
    plate = job.get("layer_frame") == {"u": [1, 0, 0], "v": [0, 1, 0], "w": [0, 0, 1]} and "build" in job
    if job.get("frame") != "machine" and not plate:  # a build's plate frame is the layer frame
        die("%s: slice with --set frame=machine (the layer frame)" % path)
    for L in d["layers"]:  # the layer frame: one height w a layer
        ws = [p[2] for c in L["contours"] for p in c["points"]]
        ws += [v[e][2] for v in L["vectors"] for e in ("from", "to")]
        if ws and max(ws) - min(ws) > 1e-6 * (1 + abs(max(ws))):
            die("%s: layer %d's points are not in one plane w = const (the layer frame?)" % (path, L["index"]))
    layers = [Layer(L, h) for L in d["layers"]]
    return d, layers


def in_spans(x, spans):
    for a, b in spans:
        if a < x < b:
            return True
    return False


def grid_rows(regions, step, maxn):
    """a grid over the union of regions, row by row: (y, [x...] inside),
    the step grown until at most maxn grid nodes cover the bounding box;
    the rows' x from the regions' spans, not a test per point"""
    boxes = [r.bbox for r in regions if r.bbox]
    if not boxes:
        return []
    x0 = min(b[0] for b in boxes); y0 = min(b[1] for b in boxes)
    x1 = max(b[2] for b in boxes); y1 = max(b[3] for b in boxes)
    while ((x1 - x0) / step + 1) * ((y1 - y0) / step + 1) > maxn:
        step *= 1.25
    rows = []
    # off the round numbers the models are made of
    j = 0
    while True:
        y = y0 + (j + 0.371) * step
        if y >= y1:
            break
        j += 1
        xs = []
        for r in regions:
            for a, b in r.spans(y):
                k0 = math.ceil((a - x0) / step - 0.293)
                k1 = math.floor((b - x0) / step - 0.293)
                xs += [x0 + (k + 0.293) * step for k in range(k0, k1 + 1)]
        if xs:
            rows.append((y, sorted(set(xs))))
    return rows


def grid_points(regions, step, maxn):
    return [(x, y) for y, xs in grid_rows(regions, step, maxn) for x in xs]


def nudged(rings, inside, eps):
    """every vertex and edge midpoint of rings, moved eps into inside()"""
    out = []
    for r in rings:
        n = len(r)
        for i in range(n):
            a, b, c = r[i - 1], r[i], r[(i + 1) % n]
            def nrm(p, q):
                dx, dy = q[0] - p[0], q[1] - p[1]
                L = math.hypot(dx, dy)
                return (0.0, 0.0) if L == 0 else (-dy / L, dx / L)
            n1, n2 = nrm(a, b), nrm(b, c)
            bis = (n1[0] + n2[0], n1[1] + n2[1])
            if math.hypot(*bis) < 1e-9:
                bis = n2
            for p, d in (((b[0], b[1]), bis), (((b[0] + c[0]) / 2, (b[1] + c[1]) / 2), n2)):
                L = math.hypot(*d)
                if L == 0:
                    continue
                dirs = [(d[0] / L, d[1] / L), (-d[0] / L, -d[1] / L)]
                dirs += [(math.cos(k * math.pi / 4), math.sin(k * math.pi / 4)) for k in range(8)]
                for ux, uy in dirs:
                    q = (p[0] + eps * ux, p[1] + eps * uy)
                    if inside(*q):
                        out.append(q)
                        break
    return out


def along(v, step):
    a, b = v["from"], v["to"]
    L = math.hypot(b[0] - a[0], b[1] - a[1])
    n = max(1, int(math.ceil(L / step)))
    return [(a[0] + (b[0] - a[0]) * i / n, a[1] + (b[1] - a[1]) * i / n) for i in range(n + 1)]


def edge_points(rings, step):
    pts = []
    for r in rings:
        n = len(r)
        for i in range(n):
            pts += along({"from": r[i], "to": r[(i + 1) % n]}, step)
    return pts


class Report:
    def __init__(self, what, limit=10):
        self.what, self.limit, self.n, self.checked = what, limit, 0, 0

    def fail(self, msg):
        self.n += 1
        if self.n <= self.limit:
            print("# FAIL %s" % msg)

    def done(self, summary):
        print("# %s: %s, %d points checked, %d failures" % (self.what, summary, self.checked, self.n))
        return 1 if self.n else 0


def cmd_stands(a):
    tanv = math.tan(math.radians(a.angle)) if a.angle < 90 else INF
    d, layers = load(a.json, a.cell)
    rep = Report("stands")
    for k in range(1, len(layers)):
        L, B = layers[k], layers[k - 1]
        r = L.width * tanv
        if r == INF:
            continue
        lim = r + a.tol
        step = a.step if a.step else r / 2
        pts = []
        for y, xs in grid_rows([L.part, L.sup], step, a.max_points):
            below = B.part.spans(y) + B.sup.spans(y)
            for x in xs:
                if in_spans(x, below):  # on the layer below: stands
                    rep.checked += 1
                else:
                    pts.append((x, y))
        pts += nudged(L.part.rings + L.sup.rings, L.in_material, a.eps)
        for x, y in pts:
            rep.checked += 1
            dd = B.material_dist(x, y, 2 * lim)
            if dd > lim:
                rep.fail("layer %d (width %g, reach %g): point (%.6f, %.6f) is %s from layer %d's part and support"
                         % (L.index, L.width, r, x, y, "%.6f" % dd if dd < 2 * lim else "over %g" % (2 * lim), B.index))
    return rep.done("%d layers, angle %g, tol %g" % (len(layers), a.angle, a.tol))


def cmd_overhang(a):
    """the overhang contours are what of each layer's part stands beyond the
    reach of the part below (the part alone, not the support): grid points
    of the part farther than r + tol from the part below are in the
    overhang, those nearer than r - tol are not, and the overhang lies in
    the part"""
    tanv = math.tan(math.radians(a.angle)) if a.angle < 90 else INF
    d, layers = load(a.json, a.cell)
    rep = Report("overhang")
    for k in range(1, len(layers)):
        L, B = layers[k], layers[k - 1]
        r = L.width * tanv
        if r == INF:
            if L.over.rings:
                rep.fail("layer %d: an overhang where nothing needs support" % L.index)
            continue
        step = a.step if a.step else r / 2
        for y, xs in grid_rows([L.part], step, a.max_points):
            for x in xs:
                if L.part.bdist(x, y, 2 * a.tol) <= a.tol:
                    continue  # on the part's edge: either
                rep.checked += 1
                dd = B.part.dist(x, y, r + 2 * a.tol)
                o = L.over.inside(x, y) and L.over.bdist(x, y, 2 * a.tol) > a.tol
                edge = L.over.inside(x, y) != o
                if dd > r + a.tol and not o and not edge:
                    rep.fail("layer %d: (%.6f, %.6f) is %.6f from layer %d's part, not in the overhang"
                             % (L.index, x, y, dd, B.index))
                elif dd < r - a.tol and L.over.inside(x, y) and not edge:
                    rep.fail("layer %d: (%.6f, %.6f) is in the overhang, %.6f from layer %d's part (reach %g)"
                             % (L.index, x, y, dd, B.index, r))
        for x, y in edge_points(L.over.rings, step):
            rep.checked += 1
            if not L.part.inside(x, y) and L.part.bdist(x, y, 2 * a.tol) > a.tol:
                rep.fail("layer %d: the overhang's (%.6f, %.6f) is outside the part" % (L.index, x, y))
    if layers and layers[0].over.rings:
        rep.fail("layer 1 (on the plate) has an overhang")
    return rep.done("%d layers, angle %g, tol %g" % (len(layers), a.angle, a.tol))


def cmd_vectors(a):
    d, layers = load(a.json, a.cell)
    rep = Report("vectors")
    nvec = 0
    G = a.gap_xy
    for i, L in enumerate(layers):
        pts = []
        for v in L.vectors:
            pts += along(v, a.sample)
        nvec += len(L.vectors)
        for x, y in pts:
            rep.checked += 1
            tooth = False
            if L.part.deep(x, y, a.tol):
                below = layers[max(0, i - a.teeth_layers):i] if a.teeth_layers > 0 else []
                if any(not B.part.deep(x, y, a.tol) for B in below):
                    tooth = True
                else:
                    rep.fail("layer %d: support vector point (%.6f, %.6f) inside the part%s"
                             % (L.index, x, y, "" if a.teeth_layers == 0 else
                                " with part under it on the %d layers below" % a.teeth_layers))
                    continue
            elif a.teeth_layers > 0 and L.part.dist(x, y, 2 * a.tol) <= a.tol:
                # on the part's outline: a tooth's wall along the part's edge
                below = layers[max(0, i - a.teeth_layers):i]
                tooth = any(not B.part.deep(x, y, a.tol) for B in below)
            if tooth:
                continue
            q = L.sup.dist(x, y, 2 * a.tol)
            if q > a.tol:
                rep.fail("layer %d: support vector point (%.6f, %.6f) %.6f outside the support region"
                         % (L.index, x, y, q))
            if G is not None:
                q = L.part.dist(x, y, G + a.tol)
                if q < G - a.tol:
                    rep.fail("layer %d: support vector point (%.6f, %.6f) %.6f from the part (gap %g)"
                             % (L.index, x, y, q, G))
        if G is not None:
            for x, y in edge_points(L.sup.rings, a.sample):
                rep.checked += 1
                q = L.part.dist(x, y, G + a.tol)
                if q < G - a.tol:
                    rep.fail("layer %d: support contour point (%.6f, %.6f) %.6f from the part (gap %g)"
                             % (L.index, x, y, q, G))
    if nvec == 0 and not a.allow_empty:
        rep.fail("no support vectors at all")
    return rep.done("%d layers, %d support vectors, teeth layers %d%s"
                    % (len(layers), nvec, a.teeth_layers, "" if G is None else ", gap_xy %g" % G))


def cmd_gapz(a):
    d, layers = load(a.json, a.cell)
    rep = Report("gapz")
    nsup = 0
    for i, L in enumerate(layers):
        pts = []
        for v in L.vectors:
            pts += along(v, a.sample)
        pts += edge_points(L.sup.rings, a.sample)
        pts += grid_points([L.sup], a.sample, a.max_points)
        nsup += L.nsup
        above = layers[i + 1:i + 1 + a.layers]
        for x, y in pts:
            rep.checked += 1
            for A in above:
                if A.part.deep(x, y, a.tol):
                    rep.fail("layer %d: support point (%.6f, %.6f) under the part of layer %d"
                             % (L.index, x, y, A.index))
                    break
    if nsup == 0:
        rep.fail("no support contours at all")
    return rep.done("%d layers, %d support contours, %d layers clear" % (len(layers), nsup, a.layers))


def cmd_none(a):
    d, layers = load(a.json, a.cell)
    rep = Report("none")
    c = sum(L.nsup for L in layers)
    v = sum(len(L.vectors) for L in layers)
    rep.checked = len(layers)
    if c or v:
        first = next(L.index for L in layers if L.nsup or L.vectors)
        rep.fail("%d support contours and %d support vectors (the first on layer %d)" % (c, v, first))
    return rep.done("%d layers" % len(layers))


def shoelace(r):
    return 0.5 * sum(r[i - 1][0] * r[i][1] - r[i][0] * r[i - 1][1] for i in range(len(r)))


def cmd_area(a):
    with open(a.json) as f:
        d = json.load(f)
    out, small = [], []
    for L in d["layers"]:
        sup = [c for c in L["contours"] if c.get("region") == "support"]
        tot = 0.0
        piece = {}
        for c in sup:
            A = abs(shoelace([(p[0], p[1]) for p in c["points"]]))
            tot += A if c["solid"] else -A
            if c["solid"]:
                piece[c["id"]] = piece.get(c["id"], 0.0) + A
            elif c.get("parent") is not None:
                piece[c["parent"]] = piece.get(c["parent"], 0.0) - A
        out.append("%.2f" % (tot + 0.0))
        if a.min is not None:
            small += ["layer %d: a support piece of %.6f" % (L["index"], v) for v in piece.values() if v < a.min]
    print(" ".join(out))
    for m in small[:10]:
        print("# FAIL %s below %g" % (m, a.min))
    return 1 if small else 0


def cmd_at(a):
    d, layers = load(a.json, a.cell)
    L = next((L for L in layers if L.index == a.layer), None)
    if L is None:
        print("no-layer")
        return 1
    print("part" if L.part.inside(a.u, a.v) else "support" if L.sup.inside(a.u, a.v) else "nothing")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    def common(p):
        p.add_argument("json")
        p.add_argument("--tol", type=float, default=1e-3)
        p.add_argument("--cell", type=float, default=1.0, help="the edge grid's cell side")
        p.add_argument("--max-points", type=int, default=20000, help="grid nodes per layer at most")
    p = sub.add_parser("stands"); common(p)
    p.add_argument("--angle", type=float, default=45)
    p.add_argument("--step", type=float, default=0, help="grid step (0: half the reach)")
    p.add_argument("--eps", type=float, default=1e-5, help="how far vertices are nudged inside")
    p.set_defaults(fn=cmd_stands)
    p = sub.add_parser("overhang"); common(p)
    p.add_argument("--angle", type=float, default=45)
    p.add_argument("--step", type=float, default=0, help="grid step (0: half the reach)")
    p.set_defaults(fn=cmd_overhang)
    p = sub.add_parser("vectors"); common(p)
    p.add_argument("--teeth-layers", type=int, default=0)
    p.add_argument("--gap-xy", type=float, default=None)
    p.add_argument("--sample", type=float, default=0.25, help="step along a vector")
    p.add_argument("--allow-empty", action="store_true")
    p.set_defaults(fn=cmd_vectors)
    p = sub.add_parser("gapz"); common(p)
    p.add_argument("--layers", type=int, required=True)
    p.add_argument("--sample", type=float, default=0.25)
    p.set_defaults(fn=cmd_gapz)
    p = sub.add_parser("none"); common(p)
    p.set_defaults(fn=cmd_none)
    p = sub.add_parser("area"); common(p)
    p.add_argument("--min", type=float, default=None)
    p.set_defaults(fn=cmd_area)
    p = sub.add_parser("at"); common(p)
    p.add_argument("layer", type=int)
    p.add_argument("u", type=float)
    p.add_argument("v", type=float)
    p.set_defaults(fn=cmd_at)
    a = ap.parse_args()
    try:
        rc = a.fn(a)
    except (OSError, ValueError, KeyError, TypeError, IndexError) as e:
        die("%s: %s: %s" % (a.json, type(e).__name__, e))
    sys.exit(rc)


if __name__ == "__main__":
    main()
