#!/usr/bin/env python3
"""Check a `lamina slice --json` run independently of lamina.

    jsoncheck.py SCHEMA RUN.json [--sls PROGRAM] [--cli PROGRAM] [--inside]

Validates RUN.json against SCHEMA with python3-jsonschema (Draft 2020-12),
then checks with its own arithmetic: every contour's points lie in its
layer's plane at the layer's height; its area is the shoelace sum of its
points projected on the plane (u, v); the layer's net area is the sum of
its contours'; ids run 1..n, a parent is an earlier contour one level up
and solids sit at even depths; vector orders run 1..n; the layer's figures
(vector count, lengths) are its vectors', and the totals are the layers'.
--sls: the contours are the SLS program's loops (sls-contours dialect:
contour Z / loop N / N lines X Y Z / endloop / endcontour) point for point,
to the program's 6 decimals. --cli: the hatch vectors (core, upskin,
downskin) are as many as the CLI ASCII program's $$HATCHES count.
--inside: the midpoint of every deposit vector (a hair below it, as the
planner takes a line on an edge: raster angle 0) is inside the section
(even-odd over the contours): the raster fills material only.
Prints one line per failure and exits 1 when there is any."""
import json
import math
import sys

import jsonschema

fails = []


def fail(msg):
    if len(fails) < 20:
        print("jsoncheck: " + msg)
    fails.append(msg)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def sub(a, b):
    return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]


def shoelace(uv):
    s = 0.0
    for i in range(len(uv)):
        x0, y0 = uv[i]
        x1, y1 = uv[(i + 1) % len(uv)]
        s += x0 * y1 - x1 * y0
    return s / 2


def inside(pt, loops):
    """Even-odd: how many loops' edges a ray to +u crosses."""
    x, y = pt
    n = 0
    for loop in loops:
        for i in range(len(loop)):
            (x0, y0), (x1, y1) = loop[i], loop[(i + 1) % len(loop)]
            if (y0 > y) != (y1 > y):
                xc = x0 + (y - y0) * (x1 - x0) / (y1 - y0)
                if xc > x:
                    n += 1
    return n % 2 == 1


def read_sls(path):
    """The loops of an SLS program: lists of (x, y, z)."""
    loops, cur, skip = [], None, False
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "hatches":
                skip = True
            elif w[0] == "endhatches":
                skip = False
            elif skip or w[0] in ("contour", "endcontour"):
                continue
            elif w[0] == "loop":
                cur = []
            elif w[0] == "endloop":
                loops.append(cur)
                cur = None
            elif cur is not None:
                cur.append(tuple(float(t) for t in w))
    return loops


def cli_hatches(path):
    n = 0
    with open(path) as f:
        for line in f:
            if line.startswith("$$HATCHES/"):
                n += int(line[len("$$HATCHES/"):].split(",")[1])
    return n


def main():
    args = sys.argv[1:]
    schema_path, run_path = args[0], args[1]
    opts = args[2:]
    with open(schema_path) as f:
        schema = json.load(f)
    with open(run_path) as f:
        run = json.load(f)
    jsonschema.Draft202012Validator.check_schema(schema)
    errors = sorted(jsonschema.Draft202012Validator(schema).iter_errors(run), key=lambda e: list(e.path))
    for e in errors:
        fail("schema: %s at %s" % (e.message, "/".join(str(p) for p in e.path)))
    if errors:
        return 1

    job = run["job"]
    pl = job["plane"]
    o, u, v, w = pl["origin"], pl["u"], pl["v"], pl["w"]
    scale = max(1.0, max(abs(b) for b in job["bbox"]))
    eps = 1e-9 * scale
    if len(run["layers"]) != job["layers"] or run["totals"]["layers"] != job["layers"]:
        fail("job.layers %d, %d layers written" % (job["layers"], len(run["layers"])))
    tot = {"contours": 0, "vectors": 0, "deposit_length": 0.0, "travel_length": 0.0}
    all_contours = []
    hatch_vectors = 0
    for k, L in enumerate(run["layers"]):
        where = "layer %d" % L["index"]
        if L["index"] != k + 1:
            fail("%s: index should be %d" % (where, k + 1))
        if not L["floor"] - eps <= L["z"] <= L["ceiling"] + eps:
            fail("%s: z %r outside [%r, %r]" % (where, L["z"], L["floor"], L["ceiling"]))
        net = 0.0
        loops = []
        for i, c in enumerate(L["contours"]):
            cw = "%s contour %d" % (where, c["id"])
            if c["id"] != i + 1:
                fail("%s: id should be %d" % (cw, i + 1))
            uv = []
            for p in c["points"]:
                d = sub(p, o)
                if abs(dot(d, w) - L["z"]) > eps:
                    fail("%s: point %r is %g off the plane" % (cw, p, dot(d, w) - L["z"]))
                uv.append((dot(d, u), dot(d, v)))
            loops.append(uv)
            a = shoelace(uv)
            if abs(a - c["area"]) > 1e-9 * max(1.0, abs(a)):
                fail("%s: area %r, the shoelace sum says %r" % (cw, c["area"], a))
            if c["solid"] != (c["area"] > 0) or c["solid"] != (c["depth"] % 2 == 0):
                fail("%s: solid %r with area %r at depth %d" % (cw, c["solid"], c["area"], c["depth"]))
            par = c["parent"]
            if (par is None) != (c["depth"] == 0):
                fail("%s: parent %r at depth %d" % (cw, par, c["depth"]))
            if par is not None and not (par < c["id"] and L["contours"][par - 1]["depth"] == c["depth"] - 1):
                fail("%s: parent %r is not an earlier contour one level up" % (cw, par))
            if c.get("region") is None:  # the section's (support regions follow it: docs/supports.md)
                net += c["area"]
                all_contours.append((L, c))
        if abs(net - L["stats"]["area"]) > 1e-9 * max(1.0, abs(net)):
            fail("%s: stats.area %r, its contours sum to %r" % (where, L["stats"]["area"], net))
        dep = trav = 0.0
        for i, vec in enumerate(L["vectors"]):
            if vec["order"] != i + 1:
                fail("%s: vector %d has order %d" % (where, i + 1, vec["order"]))
            n = math.dist(vec["from"], vec["to"])
            if vec["kind"] in ("travel", "jump"):
                trav += n
            else:
                dep += n
            if vec["kind"] in ("core", "upskin", "downskin", "support"):  # the program's $$HATCHES
                hatch_vectors += 1
            if "--inside" in opts and vec["kind"] == "deposit":
                mid = [(a + b) / 2 for a, b in zip(vec["from"], vec["to"])]
                d = sub(mid, o)
                # a line on a top edge deposits the band below it (planner.h):
                # the test point is a hair below the line, as the planner's
                if not inside((dot(d, u), dot(d, v) - 1e-7 * scale), loops):
                    fail("%s: deposit vector %d's middle %r is not in the section" % (where, vec["order"], mid))
        st = L["stats"]
        if st["vectors"] != len(L["vectors"]):
            fail("%s: stats.vectors %d, %d written" % (where, st["vectors"], len(L["vectors"])))
        for name, val in (("deposit_length", dep), ("travel_length", trav)):
            if abs(st[name] - val) > 1e-9 * max(1.0, val):
                fail("%s: stats.%s %r, its vectors sum to %r" % (where, name, st[name], val))
        tot["contours"] += len(L["contours"])
        tot["vectors"] += len(L["vectors"])
        tot["deposit_length"] += st["deposit_length"]
        tot["travel_length"] += st["travel_length"]
    T = run["totals"]
    for name, val in tot.items():
        if abs(T[name] - val) > 1e-9 * max(1.0, val):
            fail("totals.%s %r, the layers sum to %r" % (name, T[name], val))
    if T["time"] is not None:
        lt = sum(L["stats"]["time"] for L in run["layers"])
        if abs(T["time"]["total"] - lt) > 1e-9 * max(1.0, lt):
            fail("totals.time.total %r, the layers sum to %r" % (T["time"]["total"], lt))
        parts = T["time"]["exposure"] + T["time"]["jumps"] + T["time"]["recoat"]
        if abs(T["time"]["total"] - parts) > 1e-9 * max(1.0, parts):
            fail("totals.time.total %r is not exposure + jumps + recoat %r" % (T["time"]["total"], parts))

    if "--sls" in opts:
        loops = read_sls(opts[opts.index("--sls") + 1])
        if len(loops) != len(all_contours):
            fail("the program has %d loops, the JSON %d contours" % (len(loops), len(all_contours)))
        for loop, (L, c) in zip(loops, all_contours):
            if len(loop) != len(c["points"]):
                fail("layer %d contour %d: %d points, the program's loop %d"
                     % (L["index"], c["id"], len(c["points"]), len(loop)))
                continue
            for p, q in zip(c["points"], loop):
                if max(abs(a - b) for a, b in zip(p, q)) > 5e-7 + 1e-12 * scale:
                    fail("layer %d contour %d: point %r, the program has %r" % (L["index"], c["id"], p, q))
                    break
    if "--cli" in opts:
        n = cli_hatches(opts[opts.index("--cli") + 1])
        if n != hatch_vectors:
            fail("the program has %d hatch vectors, the JSON %d" % (n, hatch_vectors))
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
