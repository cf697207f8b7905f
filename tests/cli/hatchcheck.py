#!/usr/bin/env python3
"""Independent checker of hatched CLI programs (ASCII, as the cli-ascii
profile writes them, with a "//KIND//" comment line before each $$HATCHES
block, KIND core, upskin or downskin). Its own geometry: even-odd
point-in-polygon by ray crossing, shoelace areas, segment crossings and
distances; nothing from lamina or GEOS.

usage: hatchcheck.py FILE [options]
  --distance H          hatch distance of core (and skins unless given)
  --skin-distance H     hatch distance of up-skin and down-skin
  --tol T               how far a vector may leave its region (default 1e-4)
  --angle A --increment I   the hatch angle of layer i must be A + i*I
  --islands             ... or 90 degrees more (islands)
  --stripes W,O         stripes W wide overlapping by O
  --island-grid S,O     islands S wide overlapping by O
  --inset D             every vector at least D - T from every contour
  --skins N             up-skin/down-skin N layers deep: check each vector's kind
  --no-area             skip the area check (thin parts, insets)
Prints one line per failed check and a summary; exits 1 on failure."""
import math
import sys

args = sys.argv[1:]
path = args.pop(0)
opt = {"--tol": "1e-4"}
flags = set()
while args:
    a = args.pop(0)
    if a in ("--islands", "--no-area"):
        flags.add(a)
    else:
        opt[a] = args.pop(0)
H = float(opt["--distance"])
HS = float(opt.get("--skin-distance", H))
TOL = float(opt["--tol"])

# ---- read -------------------------------------------------------------------
layers = []  # each: {"z", "loops": [[(x,y)...]], "blocks": [(kind, [(x0,y0,x1,y1)])]}
kind = "core"
for line in open(path):
    line = line.strip()
    if line.startswith("//") and line.endswith("//"):
        kind = line[2:-2].split()[0]
    elif line.startswith("$$LAYER/"):
        layers.append({"z": float(line[8:]), "loops": [], "blocks": []})
    elif line.startswith("$$POLYLINE/"):
        f = line[11:].split(",")
        n = int(f[2])
        pts = [(float(f[3 + 2 * i]), float(f[4 + 2 * i])) for i in range(n)]
        assert pts[0] == pts[-1], "polyline not closed"
        layers[-1]["loops"].append(pts[:-1])
    elif line.startswith("$$HATCHES/"):
        f = line[10:].split(",")
        n = int(f[1])
        v = [tuple(float(x) for x in f[2 + 4 * i: 6 + 4 * i]) for i in range(n)]
        if kind != "support":  # support walls stand outside the part: supportcheck.py's
            layers[-1]["blocks"].append((kind, v))
        kind = "core"

# ---- geometry ---------------------------------------------------------------
def inside(loops, x, y):
    """even-odd ray crossing to +x"""
    c = False
    for L in loops:
        n = len(L)
        for i in range(n):
            x0, y0 = L[i]
            x1, y1 = L[(i + 1) % n]
            if (y0 > y) != (y1 > y):
                xc = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
                if xc > x:
                    c = not c
    return c

def edges(loops):
    out = []
    for L in loops:
        n = len(L)
        for i in range(n):
            out.append((L[i][0], L[i][1], L[(i + 1) % n][0], L[(i + 1) % n][1]))
    return out

def pdist(px, py, e):
    x0, y0, x1, y1 = e
    dx, dy = x1 - x0, y1 - y0
    l2 = dx * dx + dy * dy
    t = 0 if l2 == 0 else max(0.0, min(1.0, ((px - x0) * dx + (py - y0) * dy) / l2))
    return math.hypot(px - x0 - t * dx, py - y0 - t * dy)

def near(E, x, y, d):
    return any(pdist(x, y, e) <= d for e in E)

def cross_param(v, e):
    """parameter along v where it properly crosses e, or None"""
    ax, ay, bx, by = v
    cx, cy, dx, dy = e
    rx, ry, sx, sy = bx - ax, by - ay, dx - cx, dy - cy
    den = rx * sy - ry * sx
    if den == 0:
        return None
    t = ((cx - ax) * sy - (cy - ay) * sx) / den
    u = ((cx - ax) * ry - (cy - ay) * rx) / den
    if 0 < t < 1 and 0 <= u <= 1:
        return t
    return None

def seg_dist(v, e):
    if cross_param(v, e) is not None:
        return 0.0
    return min(pdist(v[0], v[1], e), pdist(v[2], v[3], e), pdist(e[0], e[1], v), pdist(e[2], e[3], v))

def area(loops):
    a = 0.0
    for L in loops:
        n = len(L)
        a += sum(L[i][0] * L[(i + 1) % n][1] - L[(i + 1) % n][0] * L[i][1] for i in range(n)) / 2
    return a

def perimeter(loops):
    return sum(math.hypot(e[2] - e[0], e[3] - e[1]) for e in edges(loops))

fails = []
def fail(msg):
    if len(fails) < 30:
        print("FAIL " + msg)
    fails.append(msg)

stats = {"vectors": 0, "area_checked": 0, "coverage_points": 0, "kind_checked": 0}
job_area = {"core": 0.0, "upskin": 0.0, "downskin": 0.0}
job_grid = {"core": 0.0, "upskin": 0.0, "downskin": 0.0}
nskin = int(opt.get("--skins", "0"))

for li, L in enumerate(layers):
    loops = L["loops"]
    E = edges(loops)
    A = area(loops)
    vecs = [(k, bi, v) for bi, (k, vs) in enumerate(L["blocks"]) for v in vs]
    stats["vectors"] += len(vecs)
    # containment: between two crossings of the boundary a vector is on one
    # side; each such piece (and each end) inside, or within TOL of the
    # boundary
    for k, bi, v in vecs:
        ts = sorted([t for t in (cross_param(v, e) for e in E) if t is not None] + [0.0, 1.0])
        pts = [(v[0], v[1]), (v[2], v[3])]
        pts += [(v[0] + (v[2] - v[0]) * (a + b) / 2, v[1] + (v[3] - v[1]) * (a + b) / 2) for a, b in zip(ts, ts[1:])]
        for (px, py) in pts:
            if not inside(loops, px, py) and not near(E, px, py, TOL):
                fail("layer %d: vector %s: point (%g, %g) outside its region" % (li, v, px, py))
                break
        if "--inset" in opt:
            d = min(seg_dist(v, e) for e in E)
            if d < float(opt["--inset"]) - TOL:
                fail("layer %d: vector %s only %g from a contour" % (li, v, d))
    # hatched area against the region's (regions wider than 10 hatch distances)
    hatched = sum(math.hypot(v[2] - v[0], v[3] - v[1]) * (H if k == "core" else HS) for k, bi, v in vecs)
    P = perimeter(loops)
    if "--no-area" not in flags and P > 0 and 2 * A / P >= 10 * max(H, HS):
        stats["area_checked"] += 1
        if abs(hatched - A) > 0.02 * A:
            fail("layer %d: hatched area %g, region %g (%.2f%%)" % (li, hatched, A, 100 * (hatched - A) / A))
    # the angle of the layer
    if "--angle" in opt:
        want = float(opt["--angle"]) + li * float(opt.get("--increment", "0"))
        for k, bi, v in vecs:
            ln = math.hypot(v[2] - v[0], v[3] - v[1])
            if ln < 0.05:
                continue
            a = math.degrees(math.atan2(v[3] - v[1], v[2] - v[0]))
            ok = False
            for extra in ((0, 90) if "--islands" in flags else (0,)):
                dd = (a - want - extra) % 180
                ok = ok or min(dd, 180 - dd) < 0.06
            if not ok:
                fail("layer %d: vector at %g degrees, the layer's angle is %g" % (li, a, want % 360))
                break
    # stripes: each block a band at most W + O long along the hatches;
    # pieces of one line overlap by O exactly or leave a gap outside
    if "--stripes" in opt and vecs:
        W, O = (float(x) for x in opt["--stripes"].split(","))
        want = math.radians(float(opt["--angle"]) + li * float(opt.get("--increment", "0")))
        c, s = math.cos(want), math.sin(want)
        lines = {}
        for k, bi, v in vecs:
            a0, a1 = v[0] * c + v[1] * s, v[2] * c + v[3] * s
            y = -v[0] * s + v[1] * c
            lines.setdefault(round(y / (H / 100)), []).append((min(a0, a1), max(a0, a1), bi, y))
        span = {}
        for pieces in lines.values():
            for a0, a1, bi, y in pieces:
                lo, hi = span.get(bi, (a0, a1))
                span[bi] = (min(lo, a0), max(hi, a1))
            pieces.sort()
            for p, q in zip(pieces, pieces[1:]):
                ov = p[1] - q[0]
                if ov > 0 and abs(ov - O) > 1e-3 and q[1] > p[1] + 1e-9 and q[0] > p[0] + 1e-9:
                    fail("layer %d: stripes overlap by %g, not %g" % (li, ov, O))
                elif ov < -1e-6:
                    gx = (p[1] + q[0]) / 2
                    y = p[3]
                    if inside(loops, gx * c - y * s, gx * s + y * c):
                        fail("layer %d: a gap of %g between stripes inside the region" % (li, -ov))
        for bi, (lo, hi) in span.items():
            if hi - lo > W + O + 1e-3:
                fail("layer %d: stripe %d is %g long, more than %g" % (li, bi, hi - lo, W + O))
    if "--island-grid" in opt and vecs:
        S, O = (float(x) for x in opt["--island-grid"].split(","))
        for bi, (k, vs) in enumerate(L["blocks"]):
            xs = [p for v in vs for p in (v[0], v[2])]
            ys = [p for v in vs for p in (v[1], v[3])]
            if max(xs) - min(xs) > S + O + 1e-3 or max(ys) - min(ys) > S + O + 1e-3:
                fail("layer %d: island %d spans %g x %g, more than %g" % (li, bi, max(xs) - min(xs),
                                                                           max(ys) - min(ys), S + O))
    # coverage: points well inside are exposed by a vector within half a
    # hatch distance; by two blocks only near a block's edge (the overlap)
    if vecs and ("--stripes" in opt or "--island-grid" in opt or "--coverage" in opt):
        xs = [p[0] for Lp in loops for p in Lp]
        ys = [p[1] for Lp in loops for p in Lp]
        n = 11
        O = float((opt.get("--stripes") or opt.get("--island-grid") or "0,0").split(",")[1])
        boxes = {}
        for k, bi, v in vecs:
            b = boxes.get(bi, [v[0], v[1], v[0], v[1]])
            boxes[bi] = [min(b[0], v[0], v[2]), min(b[1], v[1], v[3]), max(b[2], v[0], v[2]), max(b[3], v[1], v[3])]
        for i in range(n):
            for j in range(n):
                px = min(xs) + (max(xs) - min(xs)) * (i + 0.5) / n
                py = min(ys) + (max(ys) - min(ys)) * (j + 0.37) / n
                if not inside(loops, px, py) or near(E, px, py, 2 * H):
                    continue
                stats["coverage_points"] += 1
                by = set()
                for k, bi, v in vecs:
                    dx, dy = v[2] - v[0], v[3] - v[1]
                    l2 = dx * dx + dy * dy
                    t = ((px - v[0]) * dx + (py - v[1]) * dy) / l2
                    if -TOL / math.sqrt(l2) <= t <= 1 + TOL / math.sqrt(l2) and \
                            abs((px - v[0]) * dy - (py - v[1]) * dx) / math.sqrt(l2) <= H / 2 + 1e-3:
                        by.add(bi)
                # a hatch exposes a strip about its width wide; where an
                # island's edge cuts its lines obliquely the strips leave
                # small corners, so a point counts as exposed within 1.5 H
                # of a vector (a missing block leaves a hole far wider)
                if not by and not any(pdist(px, py, v) <= 1.5 * H for k, bi, v in vecs):
                    fail("layer %d: (%g, %g) is inside but no vector exposes it" % (li, px, py))
                for bi in by if len(by) > 1 else ():
                    b = boxes[bi]
                    edge = min(px - b[0], b[2] - px, py - b[1], b[3] - py)
                    if edge > O + H + 1e-3 and "--island-grid" in opt:
                        fail("layer %d: (%g, %g) exposed by %d blocks, %g inside block %d" % (li, px, py, len(by), edge, bi))
    # skins: a vector's kind from the layers around (missing layers are empty)
    if nskin:
        def all_in(js, x, y):
            return all(0 <= j < len(layers) and inside(layers[j]["loops"], x, y) for j in js)
        below = [li - d for d in range(1, nskin + 1)]
        above = [li + d for d in range(1, nskin + 1)]
        around = [edges(layers[j]["loops"]) for j in below + above if 0 <= j < len(layers)]
        def expected(x, y):
            if not all_in(below, x, y):
                return "downskin"
            if not all_in(above, x, y):
                return "upskin"
            return "core"
        for k, bi, v in vecs[::3]:   # every third vector: enough, and quick
            mx, my = (v[0] + v[2]) / 2, (v[1] + v[3]) / 2
            if any(near(Ea, mx, my, HS) for Ea in around):
                continue
            stats["kind_checked"] += 1
            e = expected(mx, my)
            if e != k:
                fail("layer %d: vector %s is %s, its midpoint is in the %s" % (li, v, k, e))
        for k, bi, v in vecs:
            job_area[k] += math.hypot(v[2] - v[0], v[3] - v[1]) * (H if k == "core" else HS)
        # the region's parts on a grid of the layer, classified the same way
        xs = [p[0] for Lp in loops for p in Lp]
        ys = [p[1] for Lp in loops for p in Lp]
        if xs:
            g = max(H / 2, (max(xs) - min(xs)) / 120, (max(ys) - min(ys)) / 120)  # /50 was 4% short on a frame
            x = min(xs) + g / 2
            while x < max(xs):
                y = min(ys) + g / 3
                while y < max(ys):
                    if inside(loops, x, y):
                        job_grid[expected(x, y)] += g * g
                    y += g
                x += g

if nskin:
    total = sum(job_grid.values())
    for k in job_area:
        if abs(job_area[k] - job_grid[k]) > 0.03 * total:
            fail("%s: hatched area %g, the region's %s part %g (of %g)" % (k, job_area[k], k, job_grid[k], total))
    print("# skin areas: hatched %s, grid %s" % ({k: round(v, 3) for k, v in job_area.items()},
                                                  {k: round(v, 3) for k, v in job_grid.items()}))
print("# %d layers, %d vectors, %d layer areas checked, %d coverage points, %d kinds checked, %d failures" % (
    len(layers), stats["vectors"], stats["area_checked"], stats["coverage_points"], stats["kind_checked"], len(fails)))
sys.exit(1 if fails else 0)
