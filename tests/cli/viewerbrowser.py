#!/usr/bin/env python3
"""The viewer's views in the browser against the test's own expectation
(tests/cli/viewer.t; viewercheck.py is the page's data, decoded without a browser).

    viewerbrowser.py CHROME PAGE.html RUN.json CHECK [ARGS] ... [page PAGE.html RUN.json CHECK ...]

opens the page (lamina's --html) once in headless Chromium (cdp.py, an 800 x
600 viewport) and runs each CHECK; RUN.json is the same run's --json, read
with Python's JSON parser. Each check prints one line "ok WHAT" or
"not ok WHAT: DETAIL"; viewer.t relays them as tests. The expectation of
every screenshot comes from the JSON and the viewer's documented layout and
colours (core/out/viewer.html's first comment, docs/viewer.md's last
section), never from the viewer's own answers:

  colour MODE LAYER       sample points of the drawing (vectors only: no contours,
                          no travel): where a vector of the JSON passes within
                          0.7 px and every vector within 4 px has the same colour
                          in MODE (part, style, laser, region, energy, order), the
                          3 x 3 pixels there are mostly that colour
  wrong MODE SHOWN LAYER  the picture of SHOWN checked as MODE must fail (the check
                          tells modes apart)
  hotter LAYER            energy: the part of the highest P/(v h) is redder than
                          the lowest's
  plot NAME LAYER         the plot panel: each layer's bar as tall as its figure /
                          the largest (1.5 px), the current layer marked; time with
                          several lasers: each laser's line at its time
  plotclick LAYER         a click on layer LAYER's bar shows that layer
  pick LAYER              zoomed in on a hatch vector: hovering its midpoint tells
                          its part, region, style, laser, length and order; at that
                          zoom every vector is drawn (between two the fill shows)
  ruler                   a shift-drag: the ruler's length is the drag's length in
                          the plane; the line is drawn in #e6007e
  fields LAYER            a build's lasers' fields: their dashed edges in the lasers'
                          colours
  legend MODE LAYER       the legend of a category mode (part, style, laser, region):
                          one swatch per value the layer's vectors have (and a build's
                          every part or laser), named from the JSON, in its colour
  scale MODE LAYER        the legend of order or energy: its range is the JSON's (the
                          layer's orders; the smallest and largest P/(v h) of the
                          exposure table), its bar's ends in the scale's end colours
  steps                   every layer, shown far apart, is drawn with its vectors (the times
                          printed as comments: make bench, not the test, holds them to bounds)
  early                   the first layer was drawn before the run's JSON arrived"""
import base64
import json
import math
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cdp import Browser  # noqa: E402
from pixel import decode_png  # noqa: E402

W, H = 800, 600
BAR_H, INFO_H, PLOT_H, MARGIN = 40, 28, 150, 20
PALETTE = ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
           "#bcbd22", "#17becf"]
REGION = {"contour": "#1f77b4", "core": "#ff7f0e", "upskin": "#2ca02c", "downskin": "#9467bd",
          "support": "#8c564b", "deposit": "#ff7f0e"}
GREY = "#b0b0b0"
ORDER_STOPS = [(0x0d, 0x08, 0x87), (0xcc, 0x47, 0x78), (0xf8, 0x95, 0x40)]
HEAT_STOPS = [(0x2c, 0x7b, 0xb6), (0xff, 0xff, 0xbf), (0xd7, 0x19, 0x1c)]
NB_ORDER, NB_HEAT = 48, 32
BAR, MARK = (0x9a, 0xb0, 0xc8), (0xe6, 0x00, 0x7e)
PLOT_L, PLOT_R, PLOT_T, PLOT_B = 56, 12, 20, 16


def rgb(h):
    return tuple(int(h[i:i + 2], 16) for i in (1, 3, 5))


def grad(stops, t):
    t = max(0.0, min(1.0, t))
    k, f = (0, t * 2) if t < 0.5 else (1, (t - 0.5) * 2)
    # JavaScript's Math.round: halves up
    return tuple(int(math.floor(stops[k][j] + f * (stops[k + 1][j] - stops[k][j]) + 0.5)) for j in range(3))


def close(a, b, tol=6):
    return all(abs(x - y) <= tol for x, y in zip(a, b))


def png_rows(data):
    """a screenshot's pixels: (x, y) -> (r, g, b)"""
    rows, bpp = decode_png(data)
    return lambda x, y: tuple(rows[y][x * bpp:x * bpp + 3])


class Run:
    """the JSON, and the drawing's transform from the documented layout"""

    def __init__(self, path):
        self.run = json.load(open(path))
        self.job = self.run["job"]
        P = self.job["plane"]
        self.uv = lambda p: (sum((p[i] - P["origin"][i]) * P["u"][i] for i in range(3)),
                             sum((p[i] - P["origin"][i]) * P["v"][i] for i in range(3)))
        b = self.job["bbox"]
        c = [self.uv([b[3 if i & 1 else 0], b[4 if i & 2 else 1], b[5 if i & 4 else 2]]) for i in range(8)]
        self.box = (min(p[0] for p in c), min(p[1] for p in c), max(p[0] for p in c), max(p[1] for p in c))
        self.build = self.job.get("build")

    def transform(self, plot=False, zoom=1, panx=0, pany=0):
        hd = H - BAR_H - INFO_H - (PLOT_H if plot else 0)
        du, dv = self.box[2] - self.box[0], self.box[3] - self.box[1]
        s = min((W - 2 * MARGIN) / du, (hd - 2 * MARGIN) / dv) * zoom
        cu, cv = (self.box[0] + self.box[2]) / 2, (self.box[1] + self.box[3]) / 2
        ox, oy = W / 2 + panx, BAR_H + hd / 2 + pany
        return s, (lambda u, v: (ox + (u - cu) * s, oy - (v - cv) * s)), (lambda x, y: (cu + (x - ox) / s, cv - (y - oy) / s))

    def exposed(self, k):
        """layer k's exposed vectors, (u0, v0, u1, v1, vector)"""
        out = []
        for v in self.run["layers"][k - 1]["vectors"]:
            if v["kind"] in ("jump", "travel"):
                continue
            a, b = self.uv(v["from"]), self.uv(v["to"])
            out.append((a[0], a[1], b[0], b[1], v))
        return out

    def name(self, what, n):
        for x in (self.build or {}).get(what + "s", []):
            if x[what] == n:
                return x["name"]
        return None

    def energy_table(self):
        t, lo, hi = {}, math.inf, -math.inf
        for x in self.job.get("exposure") or []:
            try:
                e = x["power"] / (x["speed"] * x["distance"])
            except (TypeError, ZeroDivisionError):
                continue
            if e > 0 and math.isfinite(e):
                t[(x.get("style") or 0, x["region"])] = e
                lo, hi = min(lo, e), max(hi, e)
        return t, lo, hi

    def expected(self, mode, k):
        """the colour function of a vector of layer k in mode"""
        vs = self.run["layers"][k - 1]["vectors"]
        top = max((v["order"] for v in vs if v["kind"] != "jump"), default=1)
        if mode == "order":
            return lambda v: grad(ORDER_STOPS, (min(NB_ORDER - 1, math.floor((v["order"] - 1) * NB_ORDER / max(1, top))) + 0.5) / NB_ORDER)
        if mode == "region":
            return lambda v: rgb(REGION[v["kind"]])
        if mode == "energy":
            t, lo, hi = self.energy_table()

            def en(v):
                e = t.get((v.get("style", 0), v["kind"]))
                if e is None:
                    return rgb(GREY)
                b = min(NB_HEAT - 1, math.floor((e - lo) / (hi - lo) * NB_HEAT)) if hi > lo else NB_HEAT - 1
                return grad(HEAT_STOPS, (b + 0.5) / NB_HEAT)
            return en
        default = {"part": 1, "style": 0, "laser": 0}[mode]

        def cat(v):
            n = v.get(mode, default)
            return rgb(PALETTE[(n - 1) % len(PALETTE)]) if 1 <= n < 255 else rgb(GREY)
        return cat


class Grid:
    """segments bucketed by cell, for the ones near a point"""

    def __init__(self, segs, cell):
        self.cell, self.cells = cell, {}
        for s in segs:
            x0, y0, x1, y1 = s[:4]
            for i in range(int(math.floor(min(x0, x1) / cell)), int(math.floor(max(x0, x1) / cell)) + 1):
                for j in range(int(math.floor(min(y0, y1) / cell)), int(math.floor(max(y0, y1) / cell)) + 1):
                    self.cells.setdefault((i, j), []).append(s)

    def near(self, x, y, r):
        i0, i1 = int(math.floor((x - r) / self.cell)), int(math.floor((x + r) / self.cell))
        j0, j1 = int(math.floor((y - r) / self.cell)), int(math.floor((y + r) / self.cell))
        cand = {}
        for i in range(i0, i1 + 1):
            for j in range(j0, j1 + 1):
                for s in self.cells.get((i, j), ()):
                    cand[id(s)] = s
        out = []
        for s in cand.values():
            d = seg_dist(x, y, s)
            if d <= r:
                out.append((d, s))
        return out


def shade_of(p, c, tol=10):
    """p is colour c or a darker shade of it (the direction lines over a filled strip are c x 0.55)"""
    cc = sum(v * v for v in c)
    t = max(0.55, min(1.0, sum(a * b for a, b in zip(p, c)) / cc)) if cc else 1.0
    return all(abs(a - t * b) <= tol for a, b in zip(p, c))


def both_sides(x, y, near):
    """vectors more than 1.5 px away on either side of the nearest one: inside hatched material"""
    d, s = min(near, key=lambda e: e[0])
    dx, dy = s[2] - s[0], s[3] - s[1]
    ln = math.hypot(dx, dy) or 1
    nx, ny = -dy / ln, dx / ln
    sides = set()
    for _, t in near:
        o = ((t[0] + t[2]) / 2 - x) * nx + ((t[1] + t[3]) / 2 - y) * ny
        if abs(o) > 1.5:
            sides.add(o > 0)
    return len(sides) == 2


def seg_dist(x, y, s):
    x0, y0, x1, y1 = s[:4]
    dx, dy = x1 - x0, y1 - y0
    l2 = dx * dx + dy * dy
    t = max(0.0, min(1.0, ((x - x0) * dx + (y - y0) * dy) / l2)) if l2 > 0 else 0.0
    return math.hypot(x0 + t * dx - x, y0 + t * dy - y)


class Page:
    def __init__(self, chrome, page, run):
        self.dir = tempfile.mkdtemp(prefix="viewerbrowser.")
        self.b = Browser(chrome, self.dir, W, H)
        self.s = self.b.page()
        self.b.send("Emulation.setDeviceMetricsOverride",
                    {"width": W, "height": H, "deviceScaleFactor": 1, "mobile": False}, session=self.s)
        self.url = "file://" + os.path.abspath(page)
        self.run = run
        self.open("")

    def open(self, h):
        self.b.send("Page.navigate", {"url": "about:blank"}, session=self.s)
        self.b.send("Page.navigate", {"url": self.url + "#" + h}, session=self.s)
        self.b.wait(self.s, "window.lamina && lamina.ready === true", timeout=60)

    def js(self, e):
        return self.b.eval(self.s, e)

    def view(self, h):
        """set the view by the hash (as a user's link would), once drawn"""
        self.js("lamina.set({zoom: 1, panx: 0, pany: 0, ruler: null})")  # a fitted view, no ruler
        self.js("location.hash = %s" % json.dumps("#" + h))
        want = dict(kv.split("=") for kv in h.split("&"))
        self.b.wait(self.s, "lamina.drawn && lamina.drawn.layer === %s && lamina.state.colour === %s && lamina.state.plot === %s"
                    % (want.get("layer", "1"), json.dumps(want.get("colour", "order")), json.dumps(want.get("plot", ""))),
                    timeout=20)

    def shot(self):
        data = self.b.send("Page.captureScreenshot", {"format": "png", "optimizeForSpeed": True}, session=self.s)["data"]
        return png_rows(base64.b64decode(data))

    def mouse(self, kind, x, y, mods=0, button="none"):
        self.b.send("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y, "modifiers": mods, "button": button,
                                                 "buttons": 1 if button == "left" else 0, "clickCount": 1}, session=self.s)

    def close(self):
        self.b.close()


def colour_check(pg, run, mode, k, px=None):
    """(checked, wrong, example): the picture px (or a new one of mode) against mode's colours"""
    if px is None:
        pg.view("layer=%d&contours=0&travel=0&colour=%s" % (k, mode))
        px = pg.shot()
    leg = pg.js("lamina.legend() && lamina.legend().box")
    s, to_px, _ = run.transform()
    colour = run.expected(mode, k)
    segs = []
    for u0, v0, u1, v1, v in run.exposed(k):
        a, b = to_px(u0, v0), to_px(u1, v1)
        segs.append((a[0], a[1], b[0], b[1], colour(v)))
    g = Grid(segs, 4)
    checked, wrong, ex = 0, 0, []
    for y in range(BAR_H + 4, H - INFO_H - 4, 8):
        for x in range(4, W - 4, 8):
            if leg and leg["x"] - 4 <= x <= leg["x"] + leg["w"] + 4 and leg["y"] - 4 <= y <= leg["y"] + leg["h"] + 4:
                continue
            if x < 200 and y > H - INFO_H - 36:  # the scale bar
                continue
            near = g.near(x + 0.5, y + 0.5, 4)
            if not near or min(d for d, _ in near) > 0.7 or len(set(sg[4] for _, sg in near)) != 1:
                continue
            if not both_sides(x + 0.5, y + 0.5, near):
                continue
            want = near[0][1][4]
            got = [px(x + i, y + j) for i in (-1, 0, 1) for j in (-1, 0, 1)]
            checked += 1
            if sum(shade_of(c, want) for c in got) < 6:
                wrong += 1
                if len(ex) < 3:
                    ex.append("(%d,%d: %s, expected %s)" % (x, y, px(x, y), want))
    return checked, wrong, " ".join(ex), px


def plot_check(pg, run, name, k):
    pg.view("layer=%d&plot=%s" % (k, name))
    px = pg.shot()
    layers = run.run["layers"]
    n = len(layers)
    x0, y0 = PLOT_L, H - INFO_H - PLOT_H + 1 + PLOT_T   # the panel's 1 px top border, then its title
    w, h = W - PLOT_L - PLOT_R, PLOT_H - 1 - PLOT_T - PLOT_B
    box = pg.js("lamina.plotBox(%s)" % json.dumps(name))
    if not box or (box["x"], box["y"], box["w"], box["h"]) != (x0, y0, w, h):
        return "not ok %s plot: its box is (%d, %d, %d, %d) as documented: %s" % (name, x0, y0, w, h, box)
    key = {"time": "time", "area": "area", "vectors": "vectors", "travel": "travel_length"}[name]
    vals = [(L["stats"].get(key) or 0) for L in layers]
    top = max(vals)
    bad = []
    for i, v in enumerate(vals):
        if i + 1 == k:
            continue
        cx = int(x0 + (i + 0.5) * w / n)
        tall = sum(1 for y in range(y0, y0 + h) if close(px(cx, y), BAR, 3))
        # lines drawn over the bar hide a few of its pixels: the bar's top is its topmost pixel
        ys = [y for y in range(y0, y0 + h) if close(px(cx, y), BAR, 3)]
        height = (y0 + h - ys[0]) if ys else 0
        want = v / top * h if top > 0 else 0
        if abs(height - want) > 1 or (want > 3 and tall < want * 0.6):
            bad.append("layer %d: %d px, expected %.1f" % (i + 1, height, want))
    mx = int(round(x0 + (k - 0.5) * w / n))
    marked = sum(1 for y in range(y0, y0 + h) if close(px(mx, y), MARK, 3)) >= h - 2
    if not marked:
        bad.append("no mark at layer %d (x %d)" % (k, mx))
    lasers = layers[0]["stats"].get("lasers") or []
    if name == "time" and len(lasers) > 1:
        for li, l0 in enumerate(lasers):
            c = rgb(PALETTE[(l0["laser"] - 1) % len(PALETTE)])
            for i, L in enumerate(layers):
                if i + 1 == k:
                    continue
                # a line ends at the first and last bars' centres: look just inside
                cx = int(x0 + (i + 0.5) * w / n) + (2 if i == 0 else -2 if i == n - 1 else 0)
                ly = y0 + h - L["stats"]["lasers"][li]["time"] / top * h
                if ly > y0 + h - 2:  # on the box's frame
                    continue
                if not any(close(px(cx, y), c, 40) for y in range(int(ly) - 2, int(ly) + 3)):
                    bad.append("laser %d's line not at layer %d's time (y %.1f)" % (l0["laser"], i + 1, ly))
    busiest = vals.index(top) + 1
    what = "%s plot: %d bars as tall as the JSON's figures (the largest at layer %d)%s, layer %d marked" % (
        name, n, busiest, ", each laser's time a line" if name == "time" and len(lasers) > 1 else "", k)
    return ("ok " + what) if not bad else ("not ok %s: %s" % (what, "; ".join(bad[:4])))


def plot_click(pg, run, k):
    n = len(run.run["layers"])
    pg.view("layer=1&plot=vectors")
    x0, y0 = PLOT_L, H - INFO_H - PLOT_H + 1 + PLOT_T   # the panel's 1 px top border, then its title
    w, h = W - PLOT_L - PLOT_R, PLOT_H - 1 - PLOT_T - PLOT_B
    x, y = x0 + (k - 0.5) * w / n, y0 + h - 2
    pg.mouse("mousePressed", x, y, button="left")
    pg.mouse("mouseReleased", x, y, button="left")
    pg.b.wait(pg.s, "lamina.drawn.layer === %d" % k, timeout=10)
    px = pg.shot()
    mx = int(round(x0 + (k - 0.5) * w / n))
    marked = sum(1 for yy in range(y0, y0 + h) if close(px(mx, yy), MARK, 3)) >= h - 2
    hashed = pg.js("location.hash").startswith("#layer=%d&" % k)
    ok = marked and hashed
    return "%s a click on layer %d's bar goes to layer %d (the mark and the hash follow)%s" % (
        "ok" if ok else "not ok", k, k, "" if ok else ": mark %s, hash %s" % (marked, pg.js("location.hash")))


def pick_check(pg, run, k):
    vs = [e for e in run.exposed(k) if e[4]["kind"] not in ("contour",)]
    # the longest hatch vector of the last part: a known one
    part = max(e[4].get("part", 1) for e in vs)
    mine = [e for e in vs if e[4].get("part", 1) == part]
    u0, v0, u1, v1, v = max(mine, key=lambda e: math.hypot(e[2] - e[0], e[3] - e[1]))
    mu, mv = (u0 + u1) / 2, (v0 + v1) / 2
    # zoom so that hatches are 12 px apart, the midpoint in the drawing's centre
    others = sorted(seg_dist(mu, mv, e) for e in vs if e[4] is not v)
    gap = others[0] if others else 1
    s0, _, _ = run.transform()
    zoom = 12 / (gap * s0)
    _, to0, _ = run.transform(zoom=zoom)
    x, y = to0(mu, mv)
    hd = H - BAR_H - INFO_H
    panx, pany = W / 2 - x, BAR_H + hd / 2 - y
    pg.view("layer=%d&travel=0" % k)
    pg.js("lamina.set({zoom: %r, panx: %r, pany: %r})" % (zoom, panx, pany))
    _, to_px, _ = run.transform(zoom=zoom, panx=panx, pany=pany)
    x, y = to_px(mu, mv)
    pg.mouse("mouseMoved", x, y)
    pg.b.wait(pg.s, "document.getElementById('tip').style.display === 'block'", timeout=10)
    tip = pg.js("document.getElementById('tip').textContent")
    length = math.hypot(u1 - u0, v1 - v0)
    want = [("part " + run.name("part", part)) if run.name("part", part) else "part %d" % part, v["kind"], "order %d" % v["order"],
            "length %s" % ("%.4g" % length)]
    if run.build:
        want += ["style " + (run.name("style", v["style"]) or ""), "laser %d" % v["laser"]]
    miss = [w_ for w_ in want if w_ not in tip.replace("\n", " ").replace("\u00b7", "")]
    out = ["%s hovering the midpoint of layer %d's vector %d tells %s%s" % (
        "ok" if not miss else "not ok", k, v["order"], ", ".join(want), "" if not miss else ": got '%s'" % tip)]
    # zoomed in every vector is drawn: its midpoint in its colour, half way to the next one not
    pg.js("document.getElementById('tip').style.display = 'none'")
    px = pg.shot()
    col = run.expected("order", k)(v)
    on = any(close(px(int(x) + i, int(y) + j), col, 12) for i in (-1, 0, 1) for j in (-1, 0, 1))
    # the nearest other vector's direction: step 6 px across
    du, dv = (u1 - u0) / length, (v1 - v0) / length
    nx, ny = -dv, du
    offs = [p for p in (6, -6) if min(seg_dist(mu + nx * p / (s0 * zoom), mv + ny * p / (s0 * zoom), e) for e in vs) * s0 * zoom > 4]
    between = offs and not close(px(int(x + nx * offs[0]), int(y - ny * offs[0])), col, 40)
    out.append("%s zoomed in, every vector drawn: the vector's midpoint in its order colour, 6 px across it not%s" % (
        "ok" if on and between else "not ok", "" if on and between else ": %s at the midpoint (expected %s), %s" % (
            px(int(x), int(y)), col, "no free side" if not offs else px(int(x + nx * offs[0]), int(y - ny * offs[0])))))
    return out


def ruler_check(pg, run):
    pg.view("layer=1")
    s, _, to_uv = run.transform()
    a, b = (210.0, 200.0), (520.0, 380.0)
    pg.mouse("mousePressed", a[0], a[1], mods=8, button="left")
    for t in (0.3, 0.6, 1.0):
        pg.mouse("mouseMoved", a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), mods=8, button="left")
    pg.mouse("mouseReleased", b[0], b[1], mods=8, button="left")
    pg.b.wait(pg.s, "lamina.state.ruler && lamina.drawn && lamina.state.ruler.u1 !== undefined", timeout=10)
    pg.js("lamina.show(lamina.state.layer)")
    want = math.hypot(b[0] - a[0], b[1] - a[1]) / s
    got = pg.js("lamina.state.ruler.length")
    text = pg.js("lamina.ruler ? null : null")
    px = pg.shot()
    mid = px(int((a[0] + b[0]) / 2), int((a[1] + b[1]) / 2))
    ok = abs(got - want) <= 1e-6 * max(1, want) and close(mid, MARK, 30)
    del text
    return "%s ruler: a shift-drag of %.1f px measures %.6g %s (drag / scale), drawn in #e6007e%s" % (
        "ok" if ok else "not ok", math.hypot(b[0] - a[0], b[1] - a[1]), want, run.job["units"],
        "" if ok else ": got %s, midpoint %s" % (got, mid))


def legend_check(pg, run, mode, k):
    pg.view("layer=%d&colour=%s" % (k, mode))
    px = pg.shot()
    g = pg.js("lamina.legend()")
    key = {"region": "kind"}.get(mode, mode)
    default = {"part": 1, "style": 0, "laser": 0, "kind": None}[key]
    vals = set(v.get(key, default) for v in run.run["layers"][k - 1]["vectors"] if v["kind"] not in ("jump", "travel"))
    if run.build and mode in ("part", "laser"):
        vals |= set(x[mode] for x in run.build[mode + "s"])
    kinds = ["contour", "core", "upskin", "downskin", "support", "deposit", "travel", "jump"]

    def label(v):
        if mode == "region":
            return v
        if mode == "laser":
            return "laser %d" % v
        if mode == "style" and v == 0:
            return "profile"
        return run.name(mode, v) or "%s %d" % (mode, v)

    def colour(v):
        if mode == "region":
            return rgb(REGION[v])
        return rgb(PALETTE[(v - 1) % len(PALETTE)]) if v >= 1 else rgb(GREY)
    order = sorted(vals, key=lambda v: kinds.index(v) if mode == "region" else v)
    want = [label(v) for v in order]
    got = [e["label"] for e in g["entries"]] if g and g.get("entries") else []
    bad = [] if got == want else ["labels %s, expected %s" % (got, want)]
    for v, e in zip(order, g["entries"] if got == want else []):
        c = px(int(e["x"]), int(e["y"]))
        if not close(c, colour(v), 3):
            bad.append("%s's swatch %s, expected %s" % (e["label"], c, colour(v)))
    return "%s legend by %s, layer %d: %s, each swatch in its colour%s" % (
        "ok" if not bad else "not ok", mode, k, ", ".join(want), "" if not bad else ": " + "; ".join(bad))


def scale_check(pg, run, mode, k):
    pg.view("layer=%d&colour=%s" % (k, mode))
    px = pg.shot()
    g = pg.js("lamina.legend()")
    if mode == "energy":
        _, lo, hi = run.energy_table()
        stops, nb = HEAT_STOPS, NB_HEAT
    else:
        lo = 1
        hi = max(v["order"] for v in run.run["layers"][k - 1]["vectors"] if v["kind"] != "jump")
        stops, nb = ORDER_STOPS, NB_ORDER
    bad = []
    if not g or abs(g.get("min", -1) - lo) > 1e-9 * abs(lo) or abs(g.get("max", -1) - hi) > 1e-9 * abs(hi):
        bad.append("range %s .. %s, expected %s .. %s" % (g and g.get("min"), g and g.get("max"), lo, hi))
    else:
        b = g["bar"]
        for t, x in ((0.5 / nb, b["x"] + 1), (1 - 0.5 / nb, b["x"] + b["w"] - 2)):
            c = px(int(x), int(b["y"] + b["h"] / 2))
            if not close(c, grad(stops, t), 3):
                bad.append("bar at x %d: %s, expected %s" % (x, c, grad(stops, t)))
    return "%s legend of %s, layer %d: %.4g .. %.4g, the bar from the scale's first colour to its last%s" % (
        "ok" if not bad else "not ok", mode, k, lo, hi, "" if not bad else ": " + "; ".join(bad))


def fields_check(pg, run, k):
    pg.view("layer=%d&vectors=0&contours=0&travel=0" % k)
    px = pg.shot()
    _, to_px, _ = run.transform()
    bad, seen = [], 0
    for li, l in enumerate(run.build["lasers"]):
        c = rgb(PALETTE[li % len(PALETTE)])
        f = l["field"]
        for u in (f[0], f[2]):
            x = int(math.floor(to_px(u, 0)[0] + 0.5))  # on a pixel centre: that column
            if not (10 < x < W - 10):
                continue
            seen += 1
            ys = range(BAR_H + 2, H - INFO_H - 40)
            hit = sum(1 for y in ys if any(close(px(x + d, y), c, 60) for d in (-1, 0, 1)))
            if hit < len(ys) * 0.3:
                bad.append("laser %d's edge at u = %g (x %d): %d of %d px" % (l["laser"], u, x, hit, len(ys)))
    ok = seen > 0 and not bad
    return "%s lasers' fields: %d edges in view, each dashed in its laser's colour%s" % (
        "ok" if ok else "not ok", seen, "" if ok else ": " + "; ".join(bad))


def steps(pg, run):
    """every layer shown, far apart (1, n, 2, n - 1, ...): each drawn with its
    vectors. The times are printed, not held to a bound: make bench
    (tests/bench/viewer.sh) measures them."""
    n = len(run.run["layers"])
    order = []
    lo, hi = 1, n
    while lo <= hi:
        order += [lo] if lo == hi else [lo, hi]
        lo, hi = lo + 1, hi - 1
    got = pg.js("[%s].map(function (k) { var ms = lamina.show(k); var d = lamina.drawn; "
                "return [ms, d.layer, d.drawn, d.lines + d.lod]; })" % ",".join(map(str, order[1:] + [order[0]])))
    want = order[1:] + [order[0]]
    bad = [k for k, g in zip(want, got) if g[1] != k or not g[2] or (g[3] == 0) != (not has_vectors(run, k))]
    ms = sorted(g[0] for g in got)
    print("# first layer drawn at %.0f ms; %d steps: slowest %.0f ms, median %.0f ms" % (
        pg.js("lamina.firstDrawn"), len(ms), ms[-1], ms[len(ms) // 2]))
    return "%s steps: each of the %d layers shown far apart is drawn, with its vectors%s" % (
        "ok" if not bad else "not ok", n, "" if not bad else " (not: %s)" % bad[:5])


def has_vectors(run, k):
    return run.run["layers"][k - 1]["stats"]["vectors"] > 0


def main():
    chrome, page, runp = sys.argv[1:4]
    run = Run(runp)
    args = sys.argv[4:]
    pg = Page(chrome, page, run)

    def head_box():
        box = pg.js("JSON.parse(document.getElementById('lamina-head').textContent).box")
        if any(abs(a - b) > 1e-9 * max(1, abs(b)) for a, b in zip(box, run.box)):
            print("not ok the head's box %s is the run's extent %s" % (box, run.box))
    head_box()
    shots = {}
    try:
        while args:
            c = args.pop(0)
            if c == "page":  # another page in the same browser
                page, runp = args.pop(0), args.pop(0)
                run = pg.run = Run(runp)
                pg.url = "file://" + os.path.abspath(page)
                pg.open("")
                head_box()
                shots = {}
            elif c == "colour":
                mode, k = args.pop(0), int(args.pop(0))
                n, bad, ex, px = colour_check(pg, run, mode, k)
                shots[(mode, k)] = px
                print("%s colour by %s, layer %d: %d of %d sample points wrong %s" % (
                    "ok" if n >= 20 and bad == 0 else "not ok", mode, k, bad, n, ex))
            elif c == "wrong":
                mode, shown, k = args.pop(0), args.pop(0), int(args.pop(0))
                n, bad, ex, _ = colour_check(pg, run, mode, k, shots[(shown, k)])
                print("%s (the picture of %s fails the check of %s: %d of %d wrong)" % (
                    "ok" if bad > 0 else "not ok", shown, mode, bad, n))
            elif c == "hotter":
                k = int(args.pop(0))
                print(hotter(pg, run, k, shots[("energy", k)]))
            elif c == "plot":
                name, k = args.pop(0), int(args.pop(0))
                print(plot_check(pg, run, name, k))
            elif c == "plotclick":
                print(plot_click(pg, run, int(args.pop(0))))
            elif c == "pick":
                for line in pick_check(pg, run, int(args.pop(0))):
                    print(line)
            elif c == "ruler":
                print(ruler_check(pg, run))
            elif c == "legend":
                mode, k = args.pop(0), int(args.pop(0))
                print(legend_check(pg, run, mode, k))
            elif c == "scale":
                mode, k = args.pop(0), int(args.pop(0))
                print(scale_check(pg, run, mode, k))
            elif c == "fields":
                print(fields_check(pg, run, int(args.pop(0))))
            elif c == "steps":
                print(steps(pg, run))
            elif c == "early":
                t = pg.js("[lamina.firstDrawn, lamina.loadedAt]")
                print("%s the first layer was drawn (%.0f ms) before the run's JSON was read (%.0f ms)" % (
                    "ok" if t[0] is not None and t[0] < t[1] else "not ok", t[0] or -1, t[1] or -1))
            else:
                raise SystemExit("viewerbrowser.py: unknown check " + c)
    finally:
        pg.close()


def hotter(pg, run, k, px):
    """the part exposed at the highest energy density shows redder than the lowest's"""
    t, lo, hi = run.energy_table()
    _, to_px, _ = run.transform()
    by_part = {}
    for u0, v0, u1, v1, v in run.exposed(k):
        e = t.get((v.get("style", 0), v["kind"]))
        if e is not None and v["kind"] != "contour":
            by_part.setdefault(v.get("part", 1), []).append((e, (u0 + u1) / 2, (v0 + v1) / 2))
    avg = {p: sum(x[0] for x in l) / len(l) for p, l in by_part.items()}
    hot, cold = max(avg, key=avg.get), min(avg, key=avg.get)

    def redness(p):
        pts = by_part[p][len(by_part[p]) // 2]
        x, y = to_px(pts[1], pts[2])
        c = px(int(x), int(y))
        return c[0] - c[2], c
    rh, ch = redness(hot), redness(cold)
    ok = avg[hot] > avg[cold] and rh[0] > 0 > ch[0]
    return "%s energy density: part %d (E %.3g) shows red, part %d (E %.3g) blue%s" % (
        "ok" if ok else "not ok", hot, avg[hot], cold, avg[cold], "" if ok else ": %s, %s" % (rh[1], ch[1]))


if __name__ == "__main__":
    main()
