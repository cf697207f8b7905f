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
DRAWS = ("svg", "g", "rect", "path", "line", "circle", "text", "defs", "linearGradient", "stop")
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
elif cmd == "texts":
    for e in root.iter(NS + "text"):
        print(ascii(e.text))
