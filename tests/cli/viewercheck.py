#!/usr/bin/env python3
"""The test's own reading of `lamina slice --html` pages (docs/viewer.md: a head,
one base64 block of varints per layer, the run's JSON with vectors summarised),
written from that page's description, not from the encoder.

  viewercheck.py compare PAGE JSON  every layer's block against the --json twin of the
                                  same run: contours (solid, depth, points, inside the
                                  head's box), vectors (kind, order, attributes, from and
                                  to within half a quantum in the layer plane, the jumps
                                  where the JSON has them); the page's lamina-run element: valid JSON,
                                  contours left out, its job, totals and each layer's
                                  stats equal to the twin's, and each layer's vectors
                                  summarised: the summary's groups (kind, attributes,
                                  count, length) those of the twin's vectors. Prints
                                  "ok: L layers, C contours, V vectors (J jumps)" or up to
                                  20 differences, and exits 1 on any
  viewercheck.py json PAGE        one line a layer, "INDEX AREA SOLIDS HOLES PARENTS_OK"
                                  (index and net area from the run element, the contours
                                  from the block; PARENTS_OK: each contour lies in as many
                                  others as its depth says, and inside one of opposite
                                  solidity one level up when it is not at depth 0), then
                                  "deposits N" (vectors of kind deposit in the blocks)
  viewercheck.py sizes PAGE       "layers L head H blocks B run R other O total T vectors V":
                                  the page's bytes by part (blocks: their base64) and the
                                  vectors the blocks hold, jumps included
  viewercheck.py head PAGE        the head's JSON (re-written by Python's json.dumps)
  viewercheck.py run PAGE         the run element's JSON text, as it is in the page
  viewercheck.py selftest         the decoder on a block worked out by hand
  viewercheck.py grid Z W H       points of a W x H screenshot of the stepped ring
                                  (tests/models/viewer/stepped.ug) at height Z and what
                                  each must show: "X,Y tint" or "X,Y background", from
                                  the part's own geometry (point in polygon, even-odd)
                                  and the viewer's documented layout (core/out/viewer.html:
                                  a 40 px bar above, 28 px below, the run's extent
                                  fitted with a 20 px margin, centred, v up). Points
                                  within 6 px of an edge, or by the scale bar, are left out."""
import base64
import json
import re
import sys

# docs/json.md: a vector's attribute is left out of the JSON at its default
# (vocab.h's LAM_ATTRS): part 1, the build's rows 0
ATTR_DEFAULT = {"part": 1, "style": 0, "laser": 0, "label": 0}
LIMIT = 1 << 30   # docs/viewer.md: every coordinate and difference fits a 31-bit integer


class PageError(Exception):
    pass


# ---- the page -----------------------------------------------------------------
HEAD_RE = re.compile(r'<script type="application/json" id="lamina-head">(.*?)</script>', re.S)
RUN_RE = re.compile(r'<script type="application/json" id="lamina-run">(.*?)</script>', re.S)
BLOCK_RE = re.compile(r'<script type="application/octet-stream" id="lamina-layer-([0-9]+)">([^<]*)</script>'
                      r'<script>lamina\.arrived\(([0-9]+)\)</script>')


class Page:
    """a page's head, its blocks (base64 text, layer K at blocks[K - 1]) and its run element's text"""

    def __init__(self, path):
        self.text = s = open(path, encoding="utf-8").read()
        h = HEAD_RE.search(s)
        r = RUN_RE.search(s)
        if not h or not r:
            raise PageError("no %s element" % ("lamina-head" if not h else "lamina-run"))
        self.head = json.loads(h.group(1))
        self.head_span, self.run_span = h.span(), r.span()
        self.run_text = r.group(1)
        self.blocks, self.block_bytes = [], 0
        last = h.end()
        for m in BLOCK_RE.finditer(s, h.end()):
            k = len(self.blocks) + 1
            if int(m.group(1)) != k or int(m.group(3)) != k:
                raise PageError("block %d: id lamina-layer-%s, arrived(%s)" % (k, m.group(1), m.group(3)))
            self.blocks.append(m.group(2))
            self.block_bytes += m.end() - m.start()
            last = m.end()
        hd = self.head
        if hd.get("format") != "lamina-viewer" or hd.get("version") != 1:
            raise PageError("head: format %r version %r" % (hd.get("format"), hd.get("version")))
        if len(self.blocks) != hd["layers"]:
            raise PageError("%d blocks, the head says %d layers" % (len(self.blocks), hd["layers"]))
        if not last <= r.start():
            raise PageError("the run element comes before the last block")
        if "<script>lamina.loaded()</script>" not in s[r.end():]:
            raise PageError("no lamina.loaded() after the run element")
        q = hd["quantum"]
        if not (isinstance(q, (int, float)) and q > 0):
            raise PageError("head: quantum %r" % q)

    def run(self):
        return json.loads(self.run_text)

    def layer(self, k):
        """layer k (1-based) decoded: (attr rows, contours, vectors), see decode_block"""
        return decode_block(b64(self.blocks[k - 1]), len(self.head["attrs"]), k)


def b64(text):
    """RFC 4648 base64 with padding, no line breaks (docs/viewer.md); bytes"""
    if len(text) % 4 or not re.fullmatch(r"[A-Za-z0-9+/]*={0,2}", text):
        raise PageError("a block is not padded base64 without line breaks")
    return base64.b64decode(text, validate=True)


# ---- a layer's block ------------------------------------------------------------
class Reader:
    def __init__(self, data, where):
        self.d, self.i, self.where = data, 0, where

    def u(self):
        """an unsigned LEB128 varint: 7 bits a byte, low first, high bit on all but the last"""
        d, i, v, shift = self.d, self.i, 0, 0
        while True:
            if i >= len(d):
                raise PageError("%s: the block ends inside a number" % self.where)
            b = d[i]
            i += 1
            v |= (b & 0x7F) << shift
            shift += 7
            if b < 0x80:
                self.i = i
                return v
            if shift > 63:
                raise PageError("%s: a varint longer than 64 bits" % self.where)

    def s(self):
        """a zigzag-coded signed number: z = (s << 1) ^ (s >> 63)"""
        z = self.u()
        return (z >> 1) ^ -(z & 1)


class Contour(tuple):
    """(solid, depth, points) with its region: None for the section's,
    "support" or "overhang" for a marked region's (docs/viewer.md)"""
    region = None


MARKS = {1: "support", 2: "overhang"}


def decode_block(data, n_attrs, k=0):
    """(rows, contours, vectors) of one block, coordinates in quanta:
    rows: lists of n_attrs values; contours: (solid, depth, [(U, V), ...]);
    vectors: (kind number, row, order, (U0, V0), (U1, V1), is_jump) in the
    layer's order, the implicit jumps as vectors of their own (kind None)"""
    r = Reader(data, "layer %d" % k)
    big = [0]

    def coord(*xs):   # the 31-bit promise
        for x in xs:
            if abs(x) >= LIMIT:
                big[0] += 1
        return xs

    rows = [[r.s() for _ in range(n_attrs)] for _ in range(r.u())]
    cu = cv = 0
    contours = []
    for _ in range(r.u()):
        n, flags = r.u(), r.u()
        pts = []
        for _ in range(n):
            du, dv = coord(r.s(), r.s())
            cu, cv = coord(cu + du, cv + dv)
            pts.append((cu, cv))
        contours.append(Contour((flags & 1 == 1, flags >> 1, pts)))
    vectors, order = [], 0
    for _ in range(r.u()):
        n, kind, row = r.u(), r.u(), r.u()
        if row >= len(rows):
            raise PageError("layer %d: a run's row %d, the block has %d" % (k, row, len(rows)))
        for _ in range(n):
            a = r.u()
            jump, z = a & 1, a >> 1
            du0 = coord((z >> 1) ^ -(z & 1))[0]
            dv0, du1, dv1 = coord(r.s(), r.s(), r.s())
            u0, v0 = coord(cu + du0, cv + dv0)
            if jump:
                order += 1
                vectors.append((None, row, order, (cu, cv), (u0, v0), True))
            cu, cv = coord(u0 + du1, v0 + dv1)
            order += 1
            vectors.append((kind, row, order, (u0, v0), (cu, cv), False))
    if r.i < len(data):   # the marked regions, with a cursor of their own
        mu = mv = 0
        nm = r.u()
        if nm == 0:
            raise PageError("layer %d: a marks part with no mark (a block without marks ends at its runs)" % k)
        for _ in range(nm):
            region, n, flags = r.u(), r.u(), r.u()
            if region not in MARKS:
                raise PageError("layer %d: a mark of region %d" % (k, region))
            pts = []
            for _ in range(n):
                du, dv = coord(r.s(), r.s())
                mu, mv = coord(mu + du, mv + dv)
                pts.append((mu, mv))
            c = Contour((flags & 1 == 1, flags >> 1, pts))
            c.region = MARKS[region]
            contours.append(c)
    if r.i != len(data):
        raise PageError("layer %d: %d bytes after the last run" % (k, len(data) - r.i))
    if big[0]:
        raise PageError("layer %d: %d coordinates or differences outside 31 bits" % (k, big[0]))
    return rows, contours, vectors


# ---- compare against the JSON twin ---------------------------------------------
class Diffs:
    def __init__(self):
        self.n = 0

    def __call__(self, msg):
        if self.n < 20:
            print("viewercheck: " + msg)
        self.n += 1


def projector(job):
    """a point of the JSON's output frame to the layer plane (u, v): docs/json.md's plane"""
    pl = job["plane"]
    o, u, v = pl["origin"], pl["u"], pl["v"]

    def uv(p):
        d = [p[i] - o[i] for i in range(3)]
        return (d[0] * u[0] + d[1] * u[1] + d[2] * u[2], d[0] * v[0] + d[1] * v[1] + d[2] * v[2])
    return uv


def compare(page, twin, diff):
    hd = page.head
    q = hd["quantum"]
    tol = q / 2 * (1 + 1e-9) + 1e-12   # half a quantum (and a double's rounding of u / q)
    kinds, names = hd["kinds"], hd["attrs"]
    uv = projector(twin["job"])
    box = hd["box"]
    if not (len(box) == 4 and box[0] <= box[2] and box[1] <= box[3]):
        diff("the head's box %s" % (box,))

    def near(qpt, p, what):
        a, b = uv(p)
        e = max(abs(qpt[0] * q - a), abs(qpt[1] * q - b))
        if e > tol:
            diff("%s: (%.9g, %.9g) in the page, (%.9g, %.9g) in the JSON: %.3g quanta apart"
                 % (what, qpt[0] * q, qpt[1] * q, a, b, e / q))

    if len(twin["layers"]) != hd["layers"]:
        diff("the page has %d layers, the JSON %d" % (hd["layers"], len(twin["layers"])))
    nc = nv = nj = 0
    for k, L in enumerate(twin["layers"][:hd["layers"]], 1):
        rows, contours, vectors = page.layer(k)
        jc = L["contours"]
        if len(contours) != len(jc):
            diff("layer %d: %d contours in the page, %d in the JSON" % (k, len(contours), len(jc)))
        for i, (pc, c) in enumerate(zip(contours, jc), 1):
            solid, depth, pts = pc
            w = "layer %d contour %d" % (k, i)
            if pc.region != c.get("region"):
                diff("%s: region %s in the page, %s in the JSON" % (w, pc.region, c.get("region")))
            if solid != c["solid"] or depth != c["depth"] or len(pts) != len(c["points"]):
                diff("%s: solid %s depth %d %d points in the page, solid %s depth %d %d points in the JSON"
                     % (w, solid, depth, len(pts), c["solid"], c["depth"], len(c["points"])))
                continue
            for j, (a, p) in enumerate(zip(pts, c["points"]), 1):
                near(a, p, "%s point %d" % (w, j))
            out = [p for p in pts if not (box[0] - q <= p[0] * q <= box[2] + q and box[1] - q <= p[1] * q <= box[3] + q)]
            if out:
                diff("%s: %d points outside the head's box %s, (%.9g, %.9g) the first"
                     % (w, len(out), box, out[0][0] * q, out[0][1] * q))
        nc += len(contours)
        jv = L["vectors"]
        if len(vectors) != len(jv):
            diff("layer %d: %d vectors in the page, %d in the JSON" % (k, len(vectors), len(jv)))
        for (kind, row, order, a, b, jump), v in zip(vectors, jv):
            w = "layer %d vector %d" % (k, order)
            name = "jump" if jump else (kinds[kind] if kind < len(kinds) else "kind %d" % kind)
            attrs = dict(zip(names, rows[row]))
            want = {n: v.get(n, ATTR_DEFAULT.get(n, 0)) for n in names}
            if name != v["kind"] or order != v["order"] or attrs != want:
                diff("%s: %s order %d %s in the page, %s order %d %s in the JSON"
                     % (w, name, order, attrs, v["kind"], v["order"], want))
                continue
            near(a, v["from"], w + " from")
            near(b, v["to"], w + " to")
            nj += jump
        nv += len(vectors)
    run = page.run()
    if run.get("format") != "lamina-run":
        diff("the run element's format is %r" % run.get("format"))
    for key in ("job", "totals"):
        if run.get(key) != twin.get(key):
            diff("the run element's %s differs from the JSON's" % key)
    rl = run.get("layers", [])
    if len(rl) != len(twin["layers"]):
        diff("the run element has %d layers, the JSON %d" % (len(rl), len(twin["layers"])))
    for a, b in zip(rl, twin["layers"]):
        if a.get("stats") != b["stats"] or a.get("index") != b["index"]:
            diff("layer %s: the run element's stats differ from the JSON's" % b["index"])
        if "contours" in a:
            diff("layer %s: the run element holds its contours" % b["index"])
        if "vectors" in a:
            diff("layer %s: the run element holds every vector, not a summary" % b["index"])
        else:
            summary_diff(a.get("summary"), b["vectors"], "layer %s" % b["index"], diff)
    return nc, nv, nj


def summary_diff(summary, vectors, where, diff):
    """the run element's summary of a layer (docs/json.md: a group per kind and
    set of attributes, in the order of its first vector, its count and summed
    length) against the twin's vectors grouped here"""
    groups = {}
    for v in vectors:
        key = tuple(sorted((k, x) for k, x in v.items() if k not in ("from", "to", "order")))
        g = groups.setdefault(key, [0, 0.0])
        g[0] += 1
        g[1] += sum((v["to"][i] - v["from"][i]) ** 2 for i in range(3)) ** 0.5
    want = [(dict(k), n, length) for k, (n, length) in groups.items()]
    got = summary if isinstance(summary, list) else []
    if len(got) != len(want):
        diff("%s: %d groups in the run element's summary, %d in the JSON's vectors" % (where, len(got), len(want)))
        return
    for g, (keys, n, length) in zip(got, want):
        rest = {k: x for k, x in g.items() if k not in ("count", "length")}
        if rest != keys or g.get("count") != n or abs(g.get("length", -1) - length) > 1e-9 * max(1, length):
            diff("%s: the summary's group %s (%s, %s), the JSON's %s (%d, %.12g)"
                 % (where, rest, g.get("count"), g.get("length"), keys, n, length))


# ---- the layers' contours as geometry ---------------------------------------------
def inside(poly, x, y):
    """ray casting: is (x, y) inside the polygon?"""
    c = False
    for (x0, y0), (x1, y1) in zip(poly, poly[1:] + poly[:1]):
        if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
            c = not c
    return c


def parents_ok(contours):
    """each contour lies in as many others as its depth says (its first point:
    contours do not touch), is solid at even depths, and (depth > 0) lies in
    one of opposite solidity one level up"""
    for i, (solid, depth, pts) in enumerate(contours):
        x, y = pts[0]
        around = [c for j, c in enumerate(contours) if j != i and inside(c[2], x, y)]
        if len(around) != depth or solid != (depth % 2 == 0):
            return False
        if depth and not any(c[1] == depth - 1 and c[0] != solid for c in around):
            return False
    return True


def seg_dist(x, y, a, b):
    (x0, y0), (x1, y1) = a, b
    dx, dy = x1 - x0, y1 - y0
    t = max(0, min(1, ((x - x0) * dx + (y - y0) * dy) / (dx * dx + dy * dy)))
    return ((x0 + t * dx - x) ** 2 + (y0 + t * dy - y) ** 2) ** 0.5


def square(h):
    return [(-h, -h), (h, -h), (h, h), (-h, h)]


# ---- a block worked out by hand ---------------------------------------------------
# attrs: 1 row (part 1 -> zigzag 2, style 0, laser 0, label 0)
# contours: 1 contour of 3 points, flags 1 (solid, depth 0): +150 (zigzag 300 = AC 02), 0;
#   0, +150; -150 (zigzag 299 = AB 02), 0  ->  (150, 0), (150, 150), (0, 150)
# runs: 1 run of 2 vectors, kind 1, row 0:
#   a = 0 << 1 | 1 (jump), dV0 -150, dU1 +150, dV1 0: a jump (0, 150) -> (0, 0), then (0, 0) -> (150, 0)
#   a = 299 << 1 = 598 (D6 04), dV0 +10 (zigzag 20 = 14), +150, 0: (0, 10) -> (150, 10)
HAND = bytes.fromhex("01 02000000 01 0301 AC0200 00AC02 AB0200 01 020100 01AB02AC0200 D60414AC0200")
HAND_WANT = ([[1, 0, 0, 0]], [(True, 0, [(150, 0), (150, 150), (0, 150)])],
             [(None, 0, 1, (0, 150), (0, 0), True), (1, 0, 2, (0, 0), (150, 0), False),
              (1, 0, 3, (0, 10), (150, 10), False)])


def selftest():
    bad = []
    got = decode_block(b64(base64.b64encode(HAND).decode()), 4)
    if got != HAND_WANT:
        bad.append("the hand-worked block decodes to %r" % (got,))
    for cut, why in ((HAND[:-1], "a block cut short"), (HAND + b"\0", "a byte after the last run"),
                     (HAND[:1] + b"\x80" * 10 + HAND[1:], "an over-long varint")):
        try:
            decode_block(cut, 4)
            bad.append(why + " is taken")
        except PageError:
            pass
    for text in ("AQID", "AQI=", "AQ=="):
        if b64(text) != bytes([1, 2, 3])[:len(base64.b64decode(text))]:
            bad.append("base64 %s" % text)
    for text in ("AQI", "AQ\nID", "AQ-D"):
        try:
            b64(text)
            bad.append("base64 %r is taken" % text)
        except PageError:
            pass
    if not parents_ok(HAND_WANT[1]) or parents_ok([(True, 1, [(0, 0), (1, 0), (0, 1)])]):
        bad.append("parents_ok")
    ring = [(True, 0, [(0, 0), (10, 0), (10, 10), (0, 10)]), (False, 1, [(2, 2), (2, 8), (8, 8), (8, 2)])]
    if not parents_ok(ring) or parents_ok([ring[0], (True, 1, ring[1][2])]):
        bad.append("parents_ok on a ring")
    for b in bad:
        print("viewercheck selftest: " + b)
    return 1 if bad else 0


def main(argv):
    cmd = argv[1]
    if cmd == "selftest":
        return selftest()
    if cmd == "compare":
        page = Page(argv[2])
        with open(argv[3], encoding="utf-8") as f:
            twin = json.load(f)
        diff = Diffs()
        nc, nv, nj = compare(page, twin, diff)
        if diff.n:
            print("viewercheck: %d differences" % diff.n)
            return 1
        print("ok: %d layers, %d contours, %d vectors (%d jumps)" % (page.head["layers"], nc, nv, nj))
        return 0
    if cmd == "json":
        page = Page(argv[2])
        run = page.run()
        assert run["format"] == "lamina-run" and run["version"] == 1
        deposits = 0
        kinds = page.head["kinds"]
        for k, L in enumerate(run["layers"], 1):
            rows, contours, vectors = page.layer(k)
            contours = [c for c in contours if c.region is None]  # the section's
            solids = sum(1 for c in contours if c[0])
            print(L["index"], "%.6g" % L["stats"]["area"], solids, len(contours) - solids, parents_ok(contours))
            deposits += sum(1 for v in vectors if v[0] is not None and kinds[v[0]] == "deposit")
        print("deposits", deposits)
        return 0
    if cmd == "sizes":
        page = Page(argv[2])
        nv = sum(len(page.layer(k)[2]) for k in range(1, page.head["layers"] + 1))
        head = page.head_span[1] - page.head_span[0]
        runb = page.run_span[1] - page.run_span[0]
        total = len(page.text.encode("utf-8"))
        print("layers %d head %d blocks %d run %d other %d total %d vectors %d"
              % (page.head["layers"], head, page.block_bytes, runb, total - head - runb - page.block_bytes, total, nv))
        return 0
    if cmd == "head":
        print(json.dumps(Page(argv[2]).head))
        return 0
    if cmd == "run":
        sys.stdout.write(Page(argv[2]).run_text)
        return 0
    if cmd == "grid":
        grid(float(argv[2]), int(argv[3]), int(argv[4]))
        return 0
    print(__doc__)
    return 2


def grid(z, W, H):
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


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv))
    except PageError as e:
        print("viewercheck: " + str(e))
        sys.exit(1)
