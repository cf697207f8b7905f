#!/usr/bin/env python3
"""check_build.py COMMAND ...: independent checks of `lamina build` runs
(issue 25) from the run's --json and its ASCII CLI program. Standard
library only; the geometry (convex hull, shoelace area, point in polygon,
segment distances) is this file's own, never lamina's. Prints nothing and
exits 0 when every check holds; else prints what failed and exits 1.

Commands:
  selftest                         the geometry on hand-worked cases
  stl KIND PATH ARGS... [ascii]    write a model: cyl R H [N], box W D H, ell A B T H
                                   (an L: A x B with arms T wide), binary STL or ASCII
  at RUN.json NAME                 the part's "at" as two repr()s: "x, y"
  arrange RUN.json PLATE MARGIN SPACING NPARTS [NAME=X,Y ...]
                                   PLATE: WxD or dD (round, centred on 0, 0)
  alone PLATE.json NAME ALONE.json the part NAME of the plate against the one part
                                   of ALONE (planned alone at the same place)
  balance RUN.json PROG.cli SLACK  the busiest laser against the ideal + one block
  fields RUN.json                  every vector inside its laser's field
  lengths A.json B.json            the same exposed length per part and kind
  gas RUN.json                     each laser's parts downstream first
  layers RUN.json PROG.cli W       $$LAYER tops, JSON z / cut / floor / ceiling
  labels RUN.json PROG.cli         the program's blocks and labels = the JSON's
  time RUN.json STDERR RECOAT      the printed total, lasers' and parts' times, the JSON totals
  styles RUN.json PROG.cli SPEC... NAME:REGION=POWER/SPEED: the part's region
                                   uses that exposure (a name prefix: NAME_*)
  layout SVG RUN.json              one footprint and name per part, the fields
  py CODE ARGS...                  run CODE (the test's own computations), sys.argv[1:] ARGS
  serve                            the commands above from standard input, one
                                   Python for a whole test (see serve())
"""
import json
import math
import re
import struct
import sys

FAILS = []


def fail(msg):
    FAILS.append(msg)


# ---- geometry ---------------------------------------------------------------

def shoelace(poly):
    """signed area, counter-clockwise positive"""
    a = 0.0
    for i in range(len(poly)):
        x0, y0 = poly[i]
        x1, y1 = poly[(i + 1) % len(poly)]
        a += x0 * y1 - x1 * y0
    return a / 2


def hull(points):
    """convex hull, counter-clockwise, no collinear points (monotone chain)"""
    pts = sorted(set(points))
    if len(pts) <= 2:
        return pts

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    lo, hi = [], []
    for p in pts:
        while len(lo) >= 2 and cross(lo[-2], lo[-1], p) <= 0:
            lo.pop()
        lo.append(p)
    for p in reversed(pts):
        while len(hi) >= 2 and cross(hi[-2], hi[-1], p) <= 0:
            hi.pop()
        hi.append(p)
    return lo[:-1] + hi[:-1]


def inside(poly, p):
    """point in polygon, even-odd rule (boundary: either)"""
    x, y = p
    c = False
    for i in range(len(poly)):
        x0, y0 = poly[i]
        x1, y1 = poly[(i + 1) % len(poly)]
        if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
            c = not c
    return c


def point_seg(p, a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    L = dx * dx + dy * dy
    t = 0.0 if L == 0 else max(0.0, min(1.0, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / L))
    return math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy)


def segs_cross(a, b, c, d):
    def o(p, q, r):
        v = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
        return (v > 0) - (v < 0)
    return o(a, b, c) * o(a, b, d) < 0 and o(c, d, a) * o(c, d, b) < 0


def seg_seg(a, b, c, d):
    if segs_cross(a, b, c, d):
        return 0.0
    return min(point_seg(a, c, d), point_seg(b, c, d), point_seg(c, a, b), point_seg(d, a, b))


def poly_dist(P, Q):
    """distance between two polygons (0 when they overlap)"""
    if inside(P, Q[0]) or inside(Q, P[0]):
        return 0.0
    best = math.inf
    for i in range(len(P)):
        a, b = P[i], P[(i + 1) % len(P)]
        for j in range(len(Q)):
            best = min(best, seg_seg(a, b, Q[j], Q[(j + 1) % len(Q)]))
    return best


def box_gap(A, B):
    """the distance between two boxes x0 y0 x1 y1 (a lower bound of their contents')"""
    dx = max(0.0, B[0] - A[2], A[0] - B[2])
    dy = max(0.0, B[1] - A[3], A[1] - B[3])
    return math.hypot(dx, dy)


def selftest():
    sq = [(0, 0), (2, 0), (2, 2), (0, 2)]
    checks = [
        (shoelace(sq), 4.0), (shoelace(sq[::-1]), -4.0),
        (shoelace([(0, 0), (4, 0), (4, 1), (1, 1), (1, 3), (0, 3)]), 6.0),  # an L
        (inside(sq, (1, 1)), True), (inside(sq, (3, 1)), False),
        (inside([(0, 0), (4, 0), (4, 1), (1, 1), (1, 3), (0, 3)], (2, 2)), False),
        (point_seg((0, 1), (-1, 0), (1, 0)), 1.0), (point_seg((3, 4), (0, 0), (0, 0)), 5.0),
        (seg_seg((0, 0), (2, 2), (0, 2), (2, 0)), 0.0), (seg_seg((0, 0), (1, 0), (4, 4), (4, 5)), 5.0),
        (poly_dist(sq, [(5, 0), (6, 0), (6, 1), (5, 1)]), 3.0),
        (poly_dist(sq, [(1, 1), (1.5, 1), (1.5, 1.5)]), 0.0),  # one inside the other
        (poly_dist(sq, [(5, 6), (6, 6), (6, 7)]), 5.0),  # corner (2, 2) to (5, 6)
        (hull([(0, 0), (1, 0), (2, 0), (1, 1), (2, 2), (0, 2), (1, 2)]), [(0, 0), (2, 0), (2, 2), (0, 2)]),
        (box_gap((0, 0, 1, 1), (4, 5, 6, 6)), 5.0), (box_gap((0, 0, 1, 1), (0.5, 0.5, 2, 2)), 0.0),
        (parse_duration("1 d 2 h 3 min"), (93780, 30)), (parse_duration("1 h 2 min 3 s"), (3723, 0.5)),
        (parse_duration("4 min 0 s"), (240, 0.5)), (parse_duration("12 s"), (12, 0.5)),
        (parse_duration("0.8 s"), (0.8, 0.05)), (parse_duration("0.05 s"), (0.05, 0.005)),
    ]
    for i, (got, want) in enumerate(checks):
        ok = got == want if not isinstance(want, float) else abs(got - want) < 1e-12
        if not ok:
            fail("selftest %d: got %r, want %r" % (i, got, want))


# ---- models -----------------------------------------------------------------

def prism(poly, h):
    """a closed prism of a convex-or-not simple polygon (ccw): its caps as a fan
    from each vertex of a star-shaped polygon would be wrong for an L, so caps
    are triangulated by ear clipping"""
    tris = []
    n = len(poly)
    for i in range(n):
        a, b = poly[i], poly[(i + 1) % n]
        tris.append(((a[0], a[1], 0), (b[0], b[1], 0), (b[0], b[1], h)))
        tris.append(((a[0], a[1], 0), (b[0], b[1], h), (a[0], a[1], h)))
    for a, b, c in ears(poly):
        tris.append(((a[0], a[1], h), (b[0], b[1], h), (c[0], c[1], h)))
        tris.append(((a[0], a[1], 0), (c[0], c[1], 0), (b[0], b[1], 0)))
    return tris


def ears(poly):
    pts = list(poly)
    out = []
    while len(pts) > 3:
        for i in range(len(pts)):
            a, b, c = pts[i - 1], pts[i], pts[(i + 1) % len(pts)]
            if shoelace([a, b, c]) <= 0:
                continue
            if any(inside([a, b, c], p) for p in pts if p not in (a, b, c)):
                continue
            out.append((a, b, c))
            del pts[i]
            break
    out.append(tuple(pts))
    return out


def stl(kind, path, args):
    ascii_ = bool(args) and args[-1] == "ascii"
    v = [float(x) for x in (args[:-1] if ascii_ else args)]
    if kind == "cyl":
        r, h = v[0], v[1]
        n = int(v[2]) if len(v) > 2 else 48
        poly = [(r * math.cos(2 * math.pi * i / n), r * math.sin(2 * math.pi * i / n)) for i in range(n)]
        tris = []
        for i in range(n):  # caps as fans from the centre
            a, b = poly[i], poly[(i + 1) % n]
            tris += [((a[0], a[1], 0), (b[0], b[1], 0), (b[0], b[1], h)), ((a[0], a[1], 0), (b[0], b[1], h), (a[0], a[1], h)),
                     ((0, 0, 0), (b[0], b[1], 0), (a[0], a[1], 0)), ((0, 0, h), (a[0], a[1], h), (b[0], b[1], h))]
    elif kind == "box":
        w, d, h = v
        tris = prism([(0, 0), (w, 0), (w, d), (0, d)], h)
    elif kind == "ell":
        a, b, t, h = v
        tris = prism([(0, 0), (a, 0), (a, t), (t, t), (t, b), (0, b)], h)
    else:
        raise SystemExit("stl: unknown kind " + kind)
    if ascii_:  # the ASCII form: facets with their normals (0: readers recompute them)
        with open(path, "w") as f:
            f.write("solid check_build\n")
            for t in tris:
                f.write(" facet normal 0 0 0\n  outer loop\n")
                for p in t:
                    f.write("   vertex %r %r %r\n" % tuple(float(c) for c in p))
                f.write("  endloop\n endfacet\n")
            f.write("endsolid check_build\n")
        return
    with open(path, "wb") as f:
        f.write(b"check_build".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            f.write(struct.pack("<3f", 0, 0, 0))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


# ---- reading runs -----------------------------------------------------------

def load(path):
    with open(path) as f:
        return json.load(f)


def build(run):
    return run["job"]["build"]


def part_of(v):
    return v.get("part", 1)  # omitted when 1


def exposed(layer):
    return [v for v in layer["vectors"] if v["kind"] != "jump"]


def style_names(run):
    return {s["style"]: s["name"] for s in build(run)["styles"]}


def parts_by_name(run):
    return {p["name"]: p for p in build(run)["parts"]}


def read_cli(path):
    """the program's layers: [(z, [(comment, cmd, id, coords)])], the labels, LAYERS"""
    layers, labels, count, comment = [], {}, None, None
    with open(path) as f:
        for line in f:
            line = line.strip()
            if line.startswith("$$LABEL/"):
                i, name = line[8:].split(",", 1)
                labels[int(i)] = name
            elif line.startswith("$$LAYERS/"):
                count = int(line[9:])
            elif line.startswith("$$LAYER/"):
                layers.append((float(line[8:]), []))
            elif line.startswith("//") and line.endswith("//"):
                comment = line[2:-2]
            elif line.startswith("$$HATCHES/") or line.startswith("$$POLYLINE/"):
                cmd, rest = line[2:].split("/", 1)
                f_ = [float(x) for x in rest.split(",")]
                if cmd == "HATCHES":
                    ident, n, xy = int(f_[0]), int(f_[1]), f_[2:]
                    if len(xy) != 4 * n:
                        fail("%s: a $$HATCHES line of %d vectors has %d numbers" % (path, n, len(xy)))
                else:
                    ident, n, xy = int(f_[0]), int(f_[2]), f_[3:]
                    if len(xy) != 2 * n:
                        fail("%s: a $$POLYLINE line of %d points has %d numbers" % (path, n, len(xy)))
                layers[-1][1].append((comment, cmd, ident, xy))
                comment = None
    return layers, labels, count


# ---- checks -----------------------------------------------------------------

def loops(vectors):
    """chain contour vectors into closed loops (a pass: each edge from the last's end)"""
    out, cur = [], []
    for v in vectors:
        a, b = tuple(v["from"][:2]), tuple(v["to"][:2])
        if cur and math.dist(cur[-1], a) > 1e-9:
            out.append(cur)
            cur = []
        if not cur:
            cur = [a]
        cur.append(b)
        if len(cur) > 2 and math.dist(cur[0], b) <= 1e-9:
            out.append(cur[:-1])
            cur = []
    if cur:
        out.append(cur)
    return out


def arrange(run, plate, margin, spacing, nparts, extra):
    """extra: NAME=X,Y a fixed part's at; NAME~AREA its section's area (NAME: or NAME_k)"""
    fixed = [e for e in extra if "=" in e]
    areas = [(e.split("~")[0], float(e.split("~")[1])) for e in extra if "~" in e]
    b = build(run)
    margin, spacing, nparts = float(margin), float(spacing), int(nparts)
    if plate.startswith("d"):
        want = {"diameter": float(plate[1:]), "margin": margin}
    else:
        w, d = plate.split("x")
        want = {"width": float(w), "depth": float(d), "margin": margin}
    if b["plate"] != want or b["spacing"] != spacing:
        fail("plate %r spacing %r, the job says %r spacing %r" % (b["plate"], b["spacing"], want, spacing))
    if len(b["parts"]) != nparts:
        fail("%d parts on the plate, the job has %d" % (len(b["parts"]), nparts))
    pts = {p["part"]: [] for p in b["parts"]}
    cont = {p["part"]: [] for p in b["parts"]}
    first_loops = {}
    for L in run["layers"]:
        per = {}
        for v in exposed(L):
            p = part_of(v)
            if p not in pts:
                fail("layer %d: a vector of part %d, which the plate has not" % (L["index"], p))
                continue
            for q in (v["from"], v["to"]):
                pts[p].append((q[0], q[1]))
                if plate.startswith("d"):
                    r = want["diameter"] / 2 - margin
                    if math.hypot(q[0], q[1]) > r + 1e-9:
                        fail("layer %d part %d: (%r, %r) is %r from the centre, past %r"
                             % (L["index"], p, q[0], q[1], math.hypot(q[0], q[1]), r))
                elif not (margin - 1e-9 <= q[0] <= want["width"] - margin + 1e-9 and
                          margin - 1e-9 <= q[1] <= want["depth"] - margin + 1e-9):
                    fail("layer %d part %d: (%r, %r) is outside the plate less its margin" % (L["index"], p, q[0], q[1]))
            if v["kind"] == "contour":
                cont[p].append((v["from"][0], v["from"][1]))
                per.setdefault(p, []).append(v)
        for p, vs in per.items():
            first_loops.setdefault(p, loops(vs))
    hulls, boxes = {}, {}
    for p in pts:
        if not cont[p]:
            fail("part %d has no contour vectors" % p)
            continue
        hulls[p] = hull(cont[p])
        xs, ys = [q[0] for q in pts[p]], [q[1] for q in pts[p]]
        boxes[p] = (min(xs), min(ys), max(xs), max(ys))
    # every part's vectors inside its own footprint box, centred on its at
    for p in b["parts"]:
        k = p["part"]
        if k not in boxes:
            continue
        bx, fb = boxes[k], p["box"]
        if not (fb[0] - 1e-9 <= bx[0] and fb[1] - 1e-9 <= bx[1] and bx[2] <= fb[2] + 1e-9 and bx[3] <= fb[3] + 1e-9):
            fail("part %s: its vectors' box %r is not inside its footprint box %r" % (p["name"], bx, fb))
        c = ((bx[0] + bx[2]) / 2, (bx[1] + bx[3]) / 2)
        if math.dist(c, p["at"]) > 0.1:  # a beam offset (0.04) and hatch ends, each side alike
            fail("part %s: its vectors are centred on %r, its at is %r" % (p["name"], c, p["at"]))
        if k in first_loops:
            outer = max(first_loops[k], key=lambda lp: abs(shoelace(lp)))
            for prefix, area in areas:
                if p["name"] == prefix or re.fullmatch(re.escape(prefix) + r"_\d+", p["name"]):
                    # the outer pass lies half a spot (0.04) inside the section: its area
                    # is the section's less about 0.04 of its perimeter
                    per = sum(math.dist(outer[i], outer[i - 1]) for i in range(len(outer)))
                    a = abs(shoelace(outer))
                    if not (area - 0.05 * per <= a <= area - 0.03 * per):
                        fail("part %s: its first layer's outer contour encloses %r mm2 (perimeter %r), the "
                             "section %r" % (p["name"], a, per, area))
    for name_at in fixed:
        name, xy = name_at.split("=")
        x, y = (float(s) for s in xy.split(","))
        p = parts_by_name(run).get(name)
        if not p:
            fail("no part %s on the plate" % name)
        elif p["at"] != [x, y]:
            fail("fixed part %s: at %r, the job says %r" % (name, p["at"], [x, y]))
    ids = sorted(hulls)
    close = (math.inf, None, None)
    for i in range(len(ids)):
        for j in range(i + 1, len(ids)):
            a, c = ids[i], ids[j]
            # the boxes' gap bounds the outlines': far apart pairs need no more (the
            # neighbours, within a mm of the spacing, are measured)
            if box_gap(boxes[a], boxes[c]) >= spacing + 1:
                continue
            d = poly_dist(hulls[a], hulls[c])
            close = min(close, (d, a, c))
            if d < spacing - 1e-9:
                fail("parts %d and %d: contours %r apart, closer than the spacing %r" % (a, c, d, spacing))
    if close[1]:
        print("# closest contours %.6f apart: parts %d and %d" % close)


def alone(plate_run, name, alone_run):
    p = parts_by_name(plate_run).get(name)
    if not p:
        return fail("no part %s on the plate" % name)
    if len(build(alone_run)["parts"]) != 1:
        return fail("the one-part job has %d parts" % len(build(alone_run)["parts"]))
    q = build(alone_run)["parts"][0]
    if q["at"] != p["at"]:
        fail("part %s: alone at %r, on the plate at %r" % (name, q["at"], p["at"]))
    sp, sa = style_names(plate_run), style_names(alone_run)

    def program(run, part, names):
        out = {}
        for L in run["layers"]:
            vs = [(v["kind"], tuple(v["from"]), tuple(v["to"]), names[v["style"]], v["laser"])
                  for v in exposed(L) if part_of(v) == part]
            if vs:
                out[L["z"]] = vs
        return out
    # its time on the plate (its own blocks, as one laser would take them) = alone: its
    # share there, which with one laser is the whole scanning time
    t = next((x["time"] for x in plate_run["totals"]["parts"] if x["part"] == p["part"]), None)
    share = alone_run["totals"]["parts"][0]["time"]
    ta = alone_run["totals"]["time"]
    if len(build(alone_run)["lasers"]) == 1 and abs(share - ta["exposure"] - ta["jumps"]) > 1e-9 * max(1, share):
        fail("part %s alone, one laser: its time %r s, the run's exposure and jumps %r s" % (
            name, share, ta["exposure"] + ta["jumps"]))
    if t is None or abs(t - share) > 1e-9 * max(1, t):
        fail("part %s: %r s on the plate, alone %r s" % (name, t, share))
    A, B = program(plate_run, p["part"], sp), program(alone_run, 1, sa)
    if sorted(A) != sorted(B):
        return fail("part %s: layers at %r on the plate, alone %r" % (name, sorted(A), sorted(B)))
    for z in sorted(A):
        a, b = A[z], B[z]
        if len({v[4] for v in a} | {v[4] for v in b}) == 1:  # one laser: the order too
            if a != b:
                k = next((i for i in range(min(len(a), len(b))) if a[i] != b[i]), min(len(a), len(b)))
                fail("part %s layer z=%r: %d vectors on the plate, %d alone; #%d: %r against %r" % (
                    name, z, len(a), len(b), k, a[k] if k < len(a) else None, b[k] if k < len(b) else None))
        elif sorted(v[:4] for v in a) != sorted(v[:4] for v in b):
            fail("part %s layer z=%r: the plate's vectors are not the part's alone" % (name, z))


def balance(run, cli, slack):
    slack = float(slack)
    prog, labels, _ = read_cli(cli)
    if len(prog) != len(run["layers"]):
        return fail("%d program layers, %d JSON layers" % (len(prog), len(run["layers"])))
    worst = 0
    for L, (z, blocks) in zip(run["layers"], prog):
        t = [x["time"] for x in L["stats"]["lasers"]]
        work = [x for x in t if x > 0]
        if not work:
            continue
        ideal = sum(work) / len(work)
        # the largest block: its exposure at the speed its comment gives, its inner
        # jumps (a hatch block's: from a vector's end to the next one's start) at
        # jump_speed 7000 with a 0.5 ms delay each, one more delay
        big = 0
        for comment, cmd, ident, xy in blocks:
            m = re.search(r"speed (\S+)", comment or "")
            speed = float(m.group(1))
            if cmd == "HATCHES":
                segs = [xy[i:i + 4] for i in range(0, len(xy), 4)]
                ex = sum(math.hypot(s[2] - s[0], s[3] - s[1]) for s in segs)
                jl = sum(math.hypot(segs[i + 1][0] - segs[i][2], segs[i + 1][1] - segs[i][3]) for i in range(len(segs) - 1))
                tb = ex / speed + jl / 7000 + 0.0005 * len(segs)
            else:
                ex = sum(math.hypot(xy[i + 2] - xy[i], xy[i + 3] - xy[i + 1]) for i in range(0, len(xy) - 2, 2))
                tb = ex / speed + 0.0005
            big = max(big, tb)
        busiest = max(t)
        worst = max(worst, busiest / ideal)
        if busiest > ideal * (1 + slack) + big:
            fail("layer %d: busiest laser %r s, ideal %r s, largest block %r s: over %r%% + one block"
                 % (L["index"], busiest, ideal, big, 100 * slack))
    print("# worst balance %.4f" % worst)


def fields(run):
    fl = {x["laser"]: x["field"] for x in build(run)["lasers"]}
    n = 0
    for L in run["layers"]:
        for v in exposed(L):
            f = fl[v["laser"]]
            for q in (v["from"], v["to"]):
                if not (f[0] - 1e-6 <= q[0] <= f[2] + 1e-6 and f[1] - 1e-6 <= q[1] <= f[3] + 1e-6):
                    n += 1
                    if n <= 5:
                        fail("layer %d: a %s vector of part %d on laser %d at (%r, %r) is outside its field %r"
                             % (L["index"], v["kind"], part_of(v), v["laser"], q[0], q[1], f))


def lengths(a, b):
    def per(run):
        out = {}
        for L in run["layers"]:
            for v in exposed(L):
                k = (L["index"], part_of(v), v["kind"])
                out[k] = out.get(k, 0) + math.dist(v["from"], v["to"])
        return out
    A, B = per(a), per(b)
    for k in sorted(set(A) | set(B)):
        x, y = A.get(k, 0), B.get(k, 0)
        if abs(x - y) > 1e-6 * max(1, x, y):
            fail("layer %d part %d %s: exposed %r mm, %r mm in the other run" % (k + (x, y)))


def gas(run):
    b = build(run)
    g = b["gas_flow"]
    centre = {p["part"]: ((p["box"][0] + p["box"][2]) / 2, (p["box"][1] + p["box"][3]) / 2) for p in b["parts"]}
    for L in run["layers"]:
        seq = {}
        for v in sorted(exposed(L), key=lambda v: v["order"]):
            s = seq.setdefault(v["laser"], [])
            if not s or s[-1] != part_of(v):
                s.append(part_of(v))
        for laser, parts in seq.items():
            if len(set(parts)) != len(parts):
                fail("layer %d laser %d: parts come back: %r" % (L["index"], laser, parts))
            key = [(-(centre[p][0] * g[0] + centre[p][1] * g[1]), p) for p in parts]
            if key != sorted(key):
                fail("layer %d laser %d: parts in the order %r, not downstream first (gas flow %r)"
                     % (L["index"], laser, parts, g))


def layers(run, cli, w):
    w = float(w)
    prog, labels, count = read_cli(cli)
    if count != len(prog) or len(prog) != len(run["layers"]) or run["job"]["layers"] != len(prog):
        fail("$$LAYERS/%r, %d $$LAYER lines, %d JSON layers" % (count, len(prog), len(run["layers"])))
    for k, (z, _) in enumerate(prog, 1):
        if abs(z - k * w) > 1e-9:
            fail("$$LAYER #%d at %r, the layer's top is %r" % (k, z, k * w))
    for k, L in enumerate(run["layers"], 1):
        want = {"index": k, "z": k * w, "floor": (k - 1) * w, "ceiling": k * w, "width": w, "cut": (k - 0.5) * w}
        for key, x in want.items():
            if abs(L[key] - x) > 1e-9:
                fail("layer %d: %s %r, expected %r" % (k, key, L[key], x))
        if any(abs(v["from"][2] - L["z"]) > 1e-9 or abs(v["to"][2] - L["z"]) > 1e-9 for v in L["vectors"]):
            fail("layer %d: a vector off the layer's top" % k)


def label_names(run):
    return {x["label"]: x["name"] for x in build(run)["labels"]}


def labels_cmd(run, cli):
    """the program's label table = the JSON's; its blocks' ids = the JSON's labels in
    order; each label's name says its vectors' part, style and laser"""
    prog, labels, _ = read_cli(cli)
    names = label_names(run)
    if labels != names:
        fail("the program's labels differ from the JSON's (%d against %d)" % (len(labels), len(names)))
    pn = {p["part"]: p["name"] for p in build(run)["parts"]}
    sn = style_names(run)
    for L, (z, blocks) in zip(run["layers"], prog):
        runs = []
        for v in exposed(L):
            want = "%s:%s:%d" % (pn[part_of(v)], sn[v["style"]], v["laser"])
            if names.get(v["label"]) != want:
                fail("layer %d: a vector labelled %r is %s" % (L["index"], names.get(v["label"]), want))
                return
            if not runs or runs[-1] != v["label"]:
                runs.append(v["label"])
        ids = []
        for _, _, ident, _ in blocks:
            if not ids or ids[-1] != ident:
                ids.append(ident)
        if ids != runs:
            fail("layer %d: the program's block ids %r... are not the JSON's labels %r..." % (L["index"], ids[:8], runs[:8]))


def parse_duration(text):
    """(seconds, half the last unit printed) of lamina's readable time"""
    m = re.fullmatch(r"(\d+) d (\d+) h (\d+) min", text)
    if m:
        return (int(m[1]) * 86400 + int(m[2]) * 3600 + int(m[3]) * 60, 30)
    m = re.fullmatch(r"(?:(?:(\d+) h )?(\d+) min )?(\d+) s", text)
    if m:
        return (int(m[1] or 0) * 3600 + int(m[2] or 0) * 60 + int(m[3]), 0.5)
    m = re.fullmatch(r"(\d+)\.(\d+) s", text)
    if m:
        return (float(text[:-2]), 0.5 * 10 ** -len(m[2]))
    raise ValueError("not a readable time: %r" % text)


def time_cmd(run, errpath, recoat):
    recoat = float(recoat)
    with open(errpath) as f:
        err = f.read()
    m = re.search(r"estimated build time (.*?) \(scanning", err)
    if not m:
        return fail("no estimated build time in: %r" % err)
    total = 0.0
    for L in run["layers"]:
        busiest = max(x["time"] for x in L["stats"]["lasers"])
        for x in L["stats"]["lasers"]:
            if abs(x["time"] - x["exposure"] - x["jumps"]) > 1e-9 * max(1, x["time"]):
                fail("layer %d laser %d: time %r is not exposure + jumps" % (L["index"], x["laser"], x["time"]))
        if abs(L["stats"]["time"] - (busiest + recoat)) > 1e-9 * max(1, busiest):
            fail("layer %d: time %r, busiest laser %r + recoat %r" % (L["index"], L["stats"]["time"], busiest, recoat))
        total += busiest + recoat
    got, half = parse_duration(m[1])
    if abs(got - total) > half + 1e-9:
        fail("printed %r (%r s), the layers add up to %r s" % (m[1], got, total))
    jt = run["totals"]["time"]["total"]
    if abs(jt - total) > 1e-6 * total:
        fail("JSON total %r, the layers add up to %r" % (jt, total))
    # the lasers' and parts' lines: each laser's time summed over the layers, each part's
    lt, pt = {}, {}
    for L in run["layers"]:
        for x in L["stats"]["lasers"]:
            lt[x["laser"]] = lt.get(x["laser"], 0) + x["time"]
        for x in L["stats"].get("parts", []):
            pt[x["part"]] = pt.get(x["part"], 0) + x["time"]
    for x in run["totals"]["lasers"]:
        if abs(x["time"] - lt.get(x["laser"], 0)) > 1e-6 * max(1, x["time"]):
            fail("JSON totals: laser %d %r, the layers add up to %r" % (x["laser"], x["time"], lt.get(x["laser"])))
    for x in run["totals"]["parts"]:
        if abs(x["time"] - pt.get(x["part"], 0)) > 1e-6 * max(1, x["time"]):
            fail("JSON totals: part %d %r, the layers add up to %r" % (x["part"], x["time"], pt.get(x["part"])))
    lm = re.search(r": lasers: (.*?)(?:; worst balance|\n)", err)
    if not lm:
        fail("no lasers line in: %r" % err)
    else:
        items = lm[1].split(", ")
        if len(items) != len(lt):
            fail("the lasers line names %d lasers, the run has %d" % (len(items), len(lt)))
        for it in items:
            k, d = re.fullmatch(r"laser (\d+) (.*)", it).groups()
            got, half = parse_duration(d)
            if abs(got - lt.get(int(k), 0)) > half + 1e-9:
                fail("laser %s: printed %r, the layers add up to %r s" % (k, d, lt.get(int(k))))
    pm = re.search(r": parts: (.*)\n", err)
    names = {p["part"]: p["name"] for p in build(run)["parts"]}
    if not pm:
        fail("no parts line in: %r" % err)
    else:
        items = pm[1].split(", ")
        if [re.match(r"\S+", it)[0] for it in items] != [names[k] for k in sorted(names)]:
            fail("the parts line names %r" % items[:5])
        for k, it in zip(sorted(names), items):
            got, half = parse_duration(it.split(" ", 1)[1])
            if abs(got - pt.get(k, 0)) > half + 1e-9:
                fail("part %s: printed %r, the layers add up to %r s" % (names[k], it, pt.get(k)))
    print("# %s = %r s" % (m[1], total))


def styles_cmd(run, cli, specs):
    prog, labels, _ = read_cli(cli)
    want = {}
    for s in specs:
        name, rest = s.split(":", 1)
        region, ps = rest.split("=")
        power, speed = ps.split("/")
        want[(name, region)] = (float(power), float(speed))
    seen = set()
    for z, blocks in prog:
        for comment, cmd, ident, xy in blocks:
            part, style, laser = labels[ident].split(":")
            m = re.fullmatch(r"(\w+) power (\S+) speed (\S+)", comment or "")
            if not m:
                fail("block %s has no exposure comment: %r" % (labels[ident], comment))
                continue
            region = m[1]
            for (name, r), (pw, sp) in want.items():
                if r == region and (part == name or re.fullmatch(re.escape(name) + r"_\d+", part)):
                    seen.add((name, r))
                    if (float(m[2]), float(m[3])) != (pw, sp):
                        fail("%s %s: %s, expected power %r speed %r" % (labels[ident], region, comment, pw, sp))
    for k in want:
        if k not in seen:
            fail("no %s block of part %s in the program" % (k[1], k[0]))


def layout(svg, run):
    with open(svg) as f:
        text = f.read()
    b = build(run)
    cls = re.findall(r'<(\w+) class="([\w-]+)"', text)
    count = {}
    for el, c in cls:
        count[c] = count.get(c, 0) + 1
    n, nl = len(b["parts"]), len(b["lasers"])
    for c, want in (("part", n), ("name", n), ("field", nl), ("field-label", nl), ("plate", 1)):
        if count.get(c, 0) != want:
            fail("layout: %d elements of class %s, expected %d" % (count.get(c, 0), c, want))
    names = re.findall(r'<text class="name"[^>]*>([^<]*)</text>', text)
    if sorted(names) != sorted(p["name"] for p in b["parts"]):
        fail("layout: names %r" % names[:5])
    # the fields where they are on the plate: the plate's rect gives the scale, y up
    pl = b["plate"]
    if "width" in pl:
        m = re.search(r'<rect class="plate" x="(\S+)" y="(\S+)" width="(\S+)" height="(\S+)"', text)
        x0, y0, pw, ph = (float(g) for g in m.groups())
        sx = pw / pl["width"]
        rects = re.findall(r'<rect class="field" x="(\S+)" y="(\S+)" width="(\S+)" height="(\S+)"', text)
        for r, las in zip(rects, b["lasers"]):
            f = las["field"]
            want = (x0 + f[0] * sx, y0 + (pl["depth"] - f[3]) * sx, (f[2] - f[0]) * sx, (f[3] - f[1]) * sx)
            if any(abs(float(g) - w) > 0.01 for g, w in zip(r, want)):
                fail("layout: laser %d's field drawn at %r, expected %r" % (las["laser"], r, want))


def command(cmd, args):
    """one command of the checker; its failures go to FAILS"""
    if cmd == "selftest":
        selftest()
    elif cmd == "stl":
        stl(args[0], args[1], args[2:])
    elif cmd == "at":
        p = parts_by_name(load(args[0]))[args[1]]
        print("%r, %r" % tuple(p["at"]))
    elif cmd == "arrange":
        arrange(load(args[0]), *args[1:5], args[5:])
    elif cmd == "alone":
        alone(load(args[0]), args[1], load(args[2]))
    elif cmd == "balance":
        balance(load(args[0]), args[1], args[2])
    elif cmd == "fields":
        fields(load(args[0]))
    elif cmd == "lengths":
        lengths(load(args[0]), load(args[1]))
    elif cmd == "gas":
        gas(load(args[0]))
    elif cmd == "layers":
        layers(load(args[0]), args[1], args[2])
    elif cmd == "labels":
        labels_cmd(load(args[0]), args[1])
    elif cmd == "time":
        time_cmd(load(args[0]), args[1], args[2])
    elif cmd == "styles":
        styles_cmd(load(args[0]), args[1], args[2:])
    elif cmd == "layout":
        layout(args[0], load(args[1]))
    elif cmd == "py":  # py CODE ARGS...: a computation of the test's, sys.argv[1:] = ARGS
        sys.argv = ["-c"] + args[1:]
        exec(args[0], {"__name__": "__main__"})
    else:
        raise SystemExit("check_build.py: unknown command " + cmd)


def report():
    """print the failures; the exit status"""
    for f in FAILS[:20]:
        print(f)
    if len(FAILS) > 20:
        print("... and %d more" % (len(FAILS) - 20))
    return 1 if FAILS else 0


def serve():
    """serve: the commands from standard input, one Python for the whole test
    (a start costs more than most checks). A request is its argument count on
    a line, then the arguments, each ended by a NUL byte; the answer is the
    command's standard output, then a line SERVE_END followed by its exit
    status (what one process per command would have printed and returned;
    an exception's traceback goes to standard error, status 1)"""
    import contextlib
    import io
    import traceback
    inp, out = sys.stdin.buffer, sys.stdout
    while True:
        line = inp.readline()
        if not line:
            return
        args = []
        for _ in range(int(line)):
            a = b""
            while not a.endswith(b"\0"):
                c = inp.read1(1) if hasattr(inp, "read1") else inp.read(1)
                if not c:
                    return
                a += c
            args.append(a[:-1].decode())
        FAILS.clear()
        buf = io.StringIO()
        try:
            with contextlib.redirect_stdout(buf):
                command(args[0], args[1:])
                rc = report()
        except SystemExit as e:
            rc = e.code if isinstance(e.code, int) else 1
            if not isinstance(e.code, int) and e.code is not None:
                sys.stderr.write(str(e.code) + "\n")
        except Exception:
            traceback.print_exc()
            rc = 1
        text = buf.getvalue()
        out.write(text + ("" if text.endswith("\n") or not text else "\n") + "\x1eSERVE_END %d\n" % rc)
        out.flush()


def main():
    cmd, args = sys.argv[1], sys.argv[2:]
    if cmd == "serve":
        return serve()
    command(cmd, args)
    sys.exit(report())


if __name__ == "__main__":
    main()
