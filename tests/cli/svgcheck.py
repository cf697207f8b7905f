#!/usr/bin/env python3
"""Facts about an SVG contact sheet of `lamina slice --svg`, read with the
standard XML parser (independently of lamina):
  svgcheck.py count FILE CLASS...   paths of these classes
  svgcheck.py dashes FILE           "dashed/travel dashed/exposed": travel and
                                    jump paths with a dash array / exposed ones with one
  svgcheck.py scale FILE            "PX UNITS": the scale bar's pixels per model unit
                                    (its length over the number in its label)
  svgcheck.py order FILE            per panel, the exposed paths' stroke colours go from
                                    dark blue to orange (red never falls, blue never
                                    rises, the last one is #f89540): "ok" or the panels not so
  svgcheck.py outside FILE SCALE UMIN VMAX RECTS
                                    exposed deposits/hatches whose midpoint lies outside
                                    the material: RECTS "u0,v0,u1,v1;..." are nested
                                    rectangles (even-odd; a solid's edge, within a
                                    pixel, is material, a hole's is not), panel pixel
                                    (x, y) is model (UMIN + x / SCALE, VMAX - y / SCALE)
  svgcheck.py inert FILE            "ok" when the sheet only draws: every element one a
                                    contact sheet has (svg g rect path line circle text
                                    defs linearGradient stop, SVG namespace), no event
                                    handler (on...) or link (href) attribute; else those
                                    that are not so
  svgcheck.py texts FILE            each <text>'s text, one a line, as Python's ascii()
  svgcheck.py captions FILE         "ok N F": the N caption lines' boxes (svg.h's
                                    estimate: n characters 0.6 font-size wide, from
                                    font-size above the baseline to a quarter below)
                                    lie inside their cell's caption band (the 34 px
                                    below its 200 px panel, within the panel's
                                    width), inside the sheet, pairwise disjoint,
                                    clear of every panel and of the title's and the
                                    footer's text boxes (those inside the sheet
                                    too); F is the smallest caption
                                    font size; else the faults
  svgcheck.py drawing FILE          "ok": every panel's drawing is clipped to its
                                    panel and every point it draws (paths, marks) lies
                                    in the panel; else the faults
  svgcheck.py scalebar FILE         "LENGTH UNITS PX": the scale bar's label and its
                                    drawn length in pixels
  svgcheck.py thinned FILE          per panel with a scan group, one line "V D P T":
                                    its caption's vector count and drawn count (V
                                    when none is said), its exposed paths, its travel
                                    and jump paths; then "note" if the sheet has one
Any command: a file that is not well-formed XML prints "not well-formed: ..." and exits 1."""
import re
import sys
import xml.etree.ElementTree as ET

NS = "{http://www.w3.org/2000/svg}"
EXPOSED = ("deposit", "contour", "core", "upskin", "downskin")
FILLS = ("deposit", "core", "upskin", "downskin")


def panels(root):
    """the scan groups, one per panel, in order"""
    return [g for g in root.iter(NS + "g") if g.get("class") == "scan"]


def paths(root):
    return list(root.iter(NS + "path"))


def points(d):
    nums = [float(x) for x in re.findall(r"-?[0-9.]+(?:e[-+]?[0-9]+)?", d)]
    return list(zip(nums[0::2], nums[1::2]))


def rgb(c):
    return tuple(int(c[i:i + 2], 16) for i in (1, 3, 5))


try:
    root = ET.parse(sys.argv[2]).getroot()
except ET.ParseError as e:
    print("not well-formed: %s" % e)
    sys.exit(1)
cmd = sys.argv[1]
DRAWS = ("svg", "g", "rect", "path", "line", "circle", "text", "defs", "linearGradient", "stop", "clipPath")
BAND = 34.0  # svg.h: LAM_SVG_CAPTION_BAND


def translate(e):
    m = re.match(r"translate\(([-0-9.e]+) ([-0-9.e]+)\)", e.get("transform") or "")
    return (float(m.group(1)), float(m.group(2))) if m else (0.0, 0.0)


def text_box(t, dx, dy, size):
    """svg.h's estimate of a line of text's box: x0 y0 x1 y1"""
    x, y, n = float(t.get("x")) + dx, float(t.get("y")) + dy, len(t.text or "")
    return (x, y - size, x + 0.6 * size * n, y + 0.25 * size)


def cells(root):
    """(dx, dy, panel rect's width and height, group) of each panel"""
    out = []
    for g in root.findall(NS + "g"):
        r = g.find(NS + "rect")
        if g.get("transform") and r is not None:
            dx, dy = translate(g)
            out.append((dx, dy, float(r.get("width")), float(r.get("height")), g))
    return out


def disjoint(a, b):
    return a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1]


def inside(a, b):
    e = 1e-6
    return a[0] >= b[0] - e and a[1] >= b[1] - e and a[2] <= b[2] + e and a[3] <= b[3] + e
if cmd == "count":
    print(sum(1 for p in paths(root) if p.get("class") in sys.argv[3:]))
elif cmd == "dashes":
    travel = [p for p in paths(root) if p.get("class") in ("travel", "jump")]
    exposed = [p for p in paths(root) if p.get("class") in EXPOSED]
    print("%d/%d %d/%d" % (sum(1 for p in travel if p.get("stroke-dasharray")), len(travel),
                           sum(1 for p in exposed if p.get("stroke-dasharray")), len(exposed)))
elif cmd == "scale":
    line = [e for e in root.iter(NS + "line") if e.get("class") == "scalebar"][0]
    text = [e for e in root.iter(NS + "text") if e.get("class") == "scalebar"][0].text
    length, units = text.split(" ", 1)
    px = abs(float(line.get("x2")) - float(line.get("x1")))
    print("%.6g %s" % (px / float(length), units))
elif cmd == "order":
    bad = []
    for k, g in enumerate(panels(root)):
        cols = [rgb(p.get("stroke")) for p in g.iter(NS + "path") if p.get("class") in EXPOSED]
        if not cols:
            continue
        mono = all(b[0] >= a[0] and b[2] <= a[2] for a, b in zip(cols, cols[1:]))
        if not mono or len(set(cols)) < 2:
            bad.append("panel %d: not monotone" % k)
    print("ok" if not bad else "; ".join(bad))
elif cmd == "outside":
    sc, umin, vmax = float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
    rects = [tuple(map(float, r.split(","))) for r in sys.argv[6].split(";")]
    n = 0
    for p in paths(root):
        if p.get("class") not in FILLS:
            continue
        (x0, y0), (x1, y1) = points(p.get("d"))[:2]
        u, v = umin + (x0 + x1) / 2 / sc, vmax - (y0 + y1) / 2 / sc
        e = 1 / sc
        inside = sum(1 for k, r in enumerate(rects)
                     if r[0] - e * (-1) ** k < u < r[2] + e * (-1) ** k
                     and r[1] - e * (-1) ** k < v < r[3] + e * (-1) ** k) % 2
        n += 0 if inside else 1
    print(n)
elif cmd == "inert":
    bad = ["<%s>" % e.tag for e in root.iter() if e.tag not in [NS + t for t in DRAWS]]
    bad += ["%s=" % a for e in root.iter() for a in e.attrib if a.lower().startswith("on") or a.endswith("href")]
    print("ok" if not bad else " ".join(bad))
elif cmd == "captions":
    bad, boxes, fonts = [], [], []
    sheet = (0, 0, float(root.get("width")), float(root.get("height")))
    panels_ = []
    for dx, dy, w, h, g in cells(root):
        panels_.append((dx, dy, dx + w, dy + h))
        band = (dx, dy + h, dx + w, dy + h + BAND)
        caps = [c for c in g.findall(NS + "g") if c.get("class") == "caption"]
        if len(caps) != 1:
            bad.append("panel at %g,%g: %d captions" % (dx, dy, len(caps)))
            continue
        size = float(caps[0].get("font-size"))
        fonts.append(size)
        for t in caps[0].findall(NS + "text"):
            b = text_box(t, dx, dy, size)
            if not inside(b, band):
                bad.append("%r outside its band" % t.text)
            if not inside(b, sheet):
                bad.append("%r outside the sheet" % t.text)
            boxes.append((b, t.text))
    others = []
    for t in root.iter(NS + "text"):
        if t.get("class") in ("title", "scalebar", "note"):
            others.append(text_box(t, 0, 0, float(t.get("font-size"))))
            if not inside(others[-1], sheet):
                bad.append("the %s %r outside the sheet" % (t.get("class"), t.text))
    for k, (b, txt) in enumerate(boxes):
        bad += ["%r overlaps %r" % (txt, t2) for b2, t2 in boxes[k + 1:] if not disjoint(b, b2)]
        bad += ["%r overlaps a panel" % txt for p in panels_ if not disjoint(b, p)]
        bad += ["%r overlaps the title or footer" % txt for o in others if not disjoint(b, o)]
    print("ok %d %g" % (len(boxes), min(fonts) if fonts else 0) if not bad else "; ".join(bad[:5]))
elif cmd == "drawing":
    bad = []
    for dx, dy, w, h, g in cells(root):
        d = [c for c in g.findall(NS + "g") if c.get("class") == "drawing"]
        if len(d) != 1 or d[0].get("clip-path") != "url(#cell)":
            bad.append("panel at %g,%g: no clipped drawing" % (dx, dy))
            continue
        for e in d[0].iter():
            if e.tag == NS + "circle":
                r = float(e.get("r"))
                pts = [(float(e.get("cx")) + s_ * r, float(e.get("cy")) + s_ * r) for s_ in (-1, 1)]
            elif e.tag == NS + "path":
                ox, oy = translate(e)
                if e.get("class") not in ("section", "hole"):
                    ox, oy = 10.0, 10.0  # the scan group's translate
                pts = [(x + ox, y + oy) for x, y in points(e.get("d"))]
            else:
                continue
            bad += ["panel at %g,%g: %s point %g,%g outside" % (dx, dy, e.get("class"), x, y)
                    for x, y in pts if not (-1e-6 <= x <= w + 1e-6 and -1e-6 <= y <= h + 1e-6)][:1]
    clip = [c for c in root.iter(NS + "clipPath") if c.get("id") == "cell"]
    if not clip:
        bad.append("no clipPath #cell")
    print("ok" if not bad else "; ".join(bad[:5]))
elif cmd == "scalebar":
    line = [e for e in root.iter(NS + "line") if e.get("class") == "scalebar"][0]
    text = [e for e in root.iter(NS + "text") if e.get("class") == "scalebar"][0].text
    print("%s %.6g" % (text, abs(float(line.get("x2")) - float(line.get("x1")))))
elif cmd == "thinned":
    for g in root.iter(NS + "g"):
        cap = [c for c in g.findall(NS + "g") if c.get("class") == "caption"]
        scan = [c for d in g.findall(NS + "g") for c in d.findall(NS + "g") if c.get("class") == "scan"]
        if not cap or not scan:
            continue
        line2 = cap[0].findall(NS + "text")[1].text
        v = re.search(r"([0-9]+) vectors?", line2).group(1)
        dm = re.search(r"([0-9]+) drawn", line2)
        ps = list(scan[0].iter(NS + "path"))
        print(v, dm.group(1) if dm else v, sum(1 for p in ps if p.get("class") in EXPOSED),
              sum(1 for p in ps if p.get("class") in ("travel", "jump")))
    if any(t.get("class") == "note" for t in root.iter(NS + "text")):
        print("note")
elif cmd == "texts":
    for e in root.iter(NS + "text"):
        print(ascii(e.text))
