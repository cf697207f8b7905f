#!/usr/bin/env python3
"""Open meshes for the repair tests (issue 24), and an independent reference.

Pure Python 3, deterministic (seeded), none of lamina's code:

  openmesh.py gen DIR
      writes DIR/CASE.stl (the broken mesh, ASCII STL with every digit of
      the doubles), DIR/CASE.closed.stl (the closed original) and
      DIR/CASE.removed.stl (the facets punched out; empty when none) for
      every case, and DIR/cases.json: what was done to each (facets removed and
      their total area, patches punched and their boundary edges, facets
      flipped, duplicates written, seam vertices moved) and a layer width
      per slicing axis giving about 30 layers.
  openmesh.py check CLOSED.stl RUN.json [--removed REMOVED.stl] [--tol-area A] [--scale F]
      every layer of a `lamina slice --json` run: its net area (solid
      contours minus holes, shoelace of the points in the layer plane)
      against the exact section of CLOSED (scaled by F) in the layer's
      plane; fails a layer when |net - section| > max(1% of section, A,
      the area of each patch of REMOVED (the facets punched out, grouped
      by shared vertices) that the plane crosses), or when a contour point
      lies off its plane. Prints one line per failing layer and a summary;
      exit 1 on any failure.
  openmesh.py edges STL        facets, vertices, boundary and non-manifold
                               edges (exact weld) and the boundary's
                               connected pieces (loops), as JSON
  openmesh.py extent STL AXIS...  the mesh's lowest and highest point and extent
                               along each AXIS (x|y|z|dx,dy,dz), as JSON, a line each
  openmesh.py ply2stl IN.ply OUT.stl|OUT.obj
      an ASCII PLY (x y z first, faces as lists) as binary STL (triangles;
      polygons fanned) or as OBJ (the PLY's coordinate text kept)

The section: each facet of an outward-wound closed mesh crossing the
plane dot(p, d) = h gives a segment, directed d x n (material on its
left seen from +d); Green's theorem sums the segments' shoelace terms
without chaining them into loops. A vertex on the plane counts as above
it, so every crossing edge is cut once, at the same point for both of its
facets, and the segments close.
"""
import json
import math
import os
import random
import struct
import sys

# ---------------------------------------------------------------- vectors

def sub(a, b): return (a[0] - b[0], a[1] - b[1], a[2] - b[2])
def dot(a, b): return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def norm(a): return math.sqrt(dot(a, a))
def unit(a):
    n = norm(a)
    return (a[0] / n, a[1] / n, a[2] / n)

def tri_area(t):
    return 0.5 * norm(cross(sub(t[1], t[0]), sub(t[2], t[0])))

def parse_axis(s):
    named = {"x": (1, 0, 0), "y": (0, 1, 0), "z": (0, 0, 1)}
    if s in named:
        return named[s]
    v = tuple(float(c) for c in s.split(","))
    return unit(v)

# ---------------------------------------------------------------- meshes
# A mesh: (vertices, faces), faces index triples wound outward.

def signed_volume(vs, fs):
    return sum(dot(vs[a], cross(vs[b], vs[c])) for a, b, c in fs) / 6.0

def outward(vs, fs):
    if signed_volume(vs, fs) < 0:
        return [(a, c, b) for a, b, c in fs]
    return fs

def sphere(radius=20.0, nlat=40, nlon=64):
    """UV sphere; returns vs, fs and band(k, j) -> the facets of quad j in
    band k (band 0 and nlat-1: the pole caps, one facet per quad)."""
    vs = [(0.0, 0.0, radius)]
    for k in range(1, nlat):
        th = math.pi * k / nlat
        for j in range(nlon):
            ph = 2 * math.pi * j / nlon
            vs.append((radius * math.sin(th) * math.cos(ph), radius * math.sin(th) * math.sin(ph),
                       radius * math.cos(th)))
    vs.append((0.0, 0.0, -radius))
    south = len(vs) - 1
    ring = lambda k, j: 1 + (k - 1) * nlon + j % nlon
    fs, quad = [], {}
    for j in range(nlon):
        quad[(0, j)] = [len(fs)]
        fs.append((0, ring(1, j), ring(1, j + 1)))
    for k in range(1, nlat - 1):
        for j in range(nlon):
            a, b, c, d = ring(k, j), ring(k + 1, j), ring(k + 1, j + 1), ring(k, j + 1)
            quad[(k, j)] = [len(fs), len(fs) + 1]
            fs += [(a, b, c), (a, c, d)]
    for j in range(nlon):
        quad[(nlat - 1, j)] = [len(fs)]
        fs.append((south, ring(nlat - 1, j + 1), ring(nlat - 1, j)))
    assert signed_volume(vs, fs) > 0
    return vs, fs, quad

def torus(R=20.0, r=8.0, nmaj=96, nmin=32):
    vs = []
    for i in range(nmaj):
        ph = 2 * math.pi * i / nmaj
        for j in range(nmin):
            th = 2 * math.pi * j / nmin
            vs.append(((R + r * math.cos(th)) * math.cos(ph), (R + r * math.cos(th)) * math.sin(ph),
                       r * math.sin(th)))
    vid = lambda i, j: (i % nmaj) * nmin + j % nmin
    fs, quad = [], {}
    for i in range(nmaj):
        for j in range(nmin):
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            quad[(i, j % nmin)] = [len(fs), len(fs) + 1]
            fs += [(a, b, c), (a, c, d)]
    fs2 = outward(vs, fs)
    return vs, fs2, quad, vid

def cube(size=20.0, n=4):
    """[0, size]^3, each face an n x n grid of squares split in two; faces
    named by their outward axis: '+x', '-x', ..."""
    vs, index, fs, named = [], {}, [], {}
    def v(p):
        key = tuple(round(c * n / size) for c in p)
        if key not in index:
            index[key] = len(vs)
            vs.append(tuple(c * size / n for c in key))
        return index[key]
    for axis in range(3):
        for side in (0, 1):
            name = ("+" if side else "-") + "xyz"[axis]
            named[name] = []
            u_ax, v_ax = (axis + 1) % 3, (axis + 2) % 3
            for i in range(n):
                for j in range(n):
                    def corner(di, dj):
                        p = [0.0, 0.0, 0.0]
                        p[axis] = side * size
                        p[u_ax] = (i + di) * size / n
                        p[v_ax] = (j + dj) * size / n
                        return v(p)
                    a, b, c, d = corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)
                    # (u, v, axis) is right-handed: a, b, c is counter-clockwise seen from +axis
                    pair = [(a, b, c), (a, c, d)] if side else [(a, c, b), (a, d, c)]
                    named[name] += [len(fs), len(fs) + 1]
                    fs += pair
    assert abs(signed_volume(vs, fs) - size ** 3) < 1e-6 * size ** 3
    return vs, fs, named

# ---------------------------------------------------------------- STL io

def write_stl_ascii(path, tris, name="openmesh"):
    with open(path, "w") as f:
        f.write("solid %s\n" % name)
        for t in tris:
            n = cross(sub(t[1], t[0]), sub(t[2], t[0]))
            ln = norm(n) or 1.0
            f.write(" facet normal %r %r %r\n  outer loop\n" % (n[0] / ln, n[1] / ln, n[2] / ln))
            for p in t:
                f.write("   vertex %r %r %r\n" % p)
            f.write("  endloop\n endfacet\n")
        f.write("endsolid %s\n" % name)

def write_stl_binary(path, tris):
    with open(path, "wb") as f:
        f.write(b"openmesh.py binary STL".ljust(80, b" "))
        f.write(struct.pack("<I", len(tris)))
        for t in tris:
            n = cross(sub(t[1], t[0]), sub(t[2], t[0]))
            ln = norm(n) or 1.0
            f.write(struct.pack("<12fH", n[0] / ln, n[1] / ln, n[2] / ln, *t[0], *t[1], *t[2], 0))

def read_obj(path):
    vs, tris = [], []
    with open(path) as f:
        for line in f:
            w = line.split()
            if w and w[0] == "v":
                vs.append((float(w[1]), float(w[2]), float(w[3])))
            elif w and w[0] == "f":
                ids = [int(x.split("/")[0]) for x in w[1:]]
                ids = [i - 1 if i > 0 else len(vs) + i for i in ids]
                tris += [(vs[ids[0]], vs[ids[k]], vs[ids[k + 1]]) for k in range(1, len(ids) - 1)]
    return tris

def read_stl(path):
    """List of triangles (three (x, y, z) tuples): STL, ASCII or binary, or
    OBJ (by its name)."""
    if path.endswith(".obj"):
        return read_obj(path)
    with open(path, "rb") as f:
        data = f.read()
    if len(data) >= 84:
        count = struct.unpack_from("<I", data, 80)[0]
        if 84 + 50 * count == len(data):
            tris = []
            for k in range(count):
                c = struct.unpack_from("<12f", data, 84 + 50 * k)
                tris.append(((c[3], c[4], c[5]), (c[6], c[7], c[8]), (c[9], c[10], c[11])))
            return tris
    tris, cur = [], []
    for line in data.decode("ascii").splitlines():
        w = line.split()
        if w and w[0] == "vertex":
            cur.append((float(w[1]), float(w[2]), float(w[3])))
            if len(cur) == 3:
                tris.append(tuple(cur))
                cur = []
    return tris

def tris_of(vs, fs):
    return [(vs[a], vs[b], vs[c]) for a, b, c in fs]

def edge_counts(tris):
    """Facets, vertices, and the edges used by one facet (boundary) or by
    more than two (non-manifold), vertices welded exactly."""
    index, edges = {}, {}
    for t in tris:
        ids = [index.setdefault(p, len(index)) for p in t]
        for k in range(3):
            a, b = ids[k], ids[(k + 1) % 3]
            key = (a, b) if a < b else (b, a)
            edges[key] = edges.get(key, 0) + 1
    # boundary loops: the open edges' connected pieces
    parent = {}
    def find(k):
        while parent.setdefault(k, k) != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k
    for (a, b), c in edges.items():
        if c == 1:
            parent[find(a)] = find(b)
    return {"facets": len(tris), "vertices": len(index),
            "boundary_loops": len({find(k) for k in list(parent)}),
            "boundary_edges": sum(1 for c in edges.values() if c == 1),
            "nonmanifold_edges": sum(1 for c in edges.values() if c > 2)}

# ---------------------------------------------------------------- section

def section_area(tris, d, h):
    """Exact area of the section of the closed, outward-wound mesh tris in
    the plane dot(p, d) = h (d a unit vector)."""
    return sections(tris, d, [h])[0]

def sections(tris, d, hs):
    """section_area at each height of hs; a facet is visited only at the
    heights within its span (a scan of 70,000 facets at 300 heights)."""
    import bisect
    order = sorted(range(len(hs)), key=lambda k: hs[k])
    sorted_h = [hs[k] for k in order]
    out = [0.0] * len(hs)
    u, v = _frame(d)
    for t in tris:
        s = [dot(p, d) for p in t]
        lo = bisect.bisect_right(sorted_h, min(s))  # heights above the lowest vertex
        hi = bisect.bisect_right(sorted_h, max(s))  # ... and at most the highest
        for k in range(lo, hi):
            out[order[k]] += _segment_term(t, d, sorted_h[k], u, v)
    return out

def _frame(d):
    # a right-handed frame (u, v, d) of the planes
    helper = (1.0, 0.0, 0.0) if abs(d[0]) < 0.9 else (0.0, 1.0, 0.0)
    u = unit(cross(helper, d))
    return u, cross(d, u)

def _segment_term(t, d, h, u, v):
    """The shoelace term, in the plane's frame (u, v), of the segment facet
    t cuts from the plane dot(p, d) = h (0 when it does not cross it)."""
    s = [dot(p, d) - h for p in t]
    above = [x >= 0 for x in s]
    if all(above) or not any(above):
        return 0.0
    pts = []
    for k in range(3):
        a, b = k, (k + 1) % 3
        if above[a] != above[b]:
            # the same point for both facets of the edge: computed from its
            # endpoints in a fixed order
            pa, pb, sa, sb = t[a], t[b], s[a], s[b]
            if pa > pb:
                pa, pb, sa, sb = pb, pa, sb, sa
            f = sa / (sa - sb)
            pts.append((pa[0] + f * (pb[0] - pa[0]), pa[1] + f * (pb[1] - pa[1]), pa[2] + f * (pb[2] - pa[2])))
    p, q = pts
    n = cross(sub(t[1], t[0]), sub(t[2], t[0]))
    if dot(sub(q, p), cross(d, n)) < 0:
        p, q = q, p
    pu, pv, qu, qv = dot(p, u), dot(p, v), dot(q, u), dot(q, v)
    return 0.5 * (pu * qv - qu * pv)

def shoelace(pts):
    s = 0.0
    for k in range(len(pts)):
        (au, av), (bu, bv) = pts[k], pts[(k + 1) % len(pts)]
        s += au * bv - bu * av
    return 0.5 * s

def patches_of(tris):
    """The removed facets grouped into patches (facets sharing a vertex)."""
    parent = list(range(len(tris)))
    def find(k):
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k
    first = {}
    for k, t in enumerate(tris):
        for p in t:
            j = first.setdefault(p, k)
            parent[find(j)] = find(k)
    groups = {}
    for k, t in enumerate(tris):
        groups.setdefault(find(k), []).append(t)
    return list(groups.values())

def check_run(closed_path, run_path, tol_area, scale=1.0, removed_path=None):
    tris = read_stl(closed_path)
    patches = [(g, sum(tri_area(t) for t in g)) for g in patches_of(read_stl(removed_path))] if removed_path else []
    if scale != 1.0:
        tris = [tuple(tuple(c * scale for c in p) for p in t) for t in tris]
    with open(run_path) as f:
        run = json.load(f)
    plane = run["job"]["plane"]
    o, u, v, w = (tuple(plane[k]) for k in ("origin", "u", "v", "w"))
    lo = [min(p[i] for t in tris for p in t) for i in range(3)]
    hi = [max(p[i] for t in tris for p in t) for i in range(3)]
    diag = norm(sub(hi, lo))
    failures, worst = [], (0.0, 0, 0.0, 0.0)
    if not run["layers"]:
        failures.append("the run has no layers")
    d = unit(w)
    secs = sections(tris, d, [layer["z"] + dot(o, w) for layer in run["layers"]])
    for layer, sec in zip(run["layers"], secs):
        z = layer["z"]
        net, off = 0.0, 0.0
        for c in layer["contours"]:
            rel = [sub(p, o) for p in c["points"]]
            off = max([off] + [abs(dot(r, w) - z) for r in rel])
            a = abs(shoelace([(dot(r, u), dot(r, v)) for r in rel]))
            net += a if c["solid"] else -a
        diff = net - sec
        # the filled holes' own area: of each patch the plane crosses
        h = z + dot(o, w)
        crossed = sum(a for g, a in patches
                      if min(dot(p, d) for t in g for p in t) < h < max(dot(p, d) for t in g for p in t))
        tol = max(0.01 * abs(sec), tol_area, crossed, 1e-9 * diag * diag)
        if abs(diff) / tol >= worst[0]:
            worst = (abs(diff) / tol, layer["index"], diff, tol)
        if abs(diff) > tol:
            failures.append("layer %d (z=%.6g): net area %.6g, section %.6g, diff %.4g > tolerance %.4g"
                            % (layer["index"], z, net, sec, diff, tol))
        if off > 1e-6 * diag:
            failures.append("layer %d (z=%.6g): a contour point %.3g off its plane" % (layer["index"], z, off))
    for line in failures:
        print(line)
    print("# %d layers checked, %d failures; largest |diff| / tolerance %.3g (layer %d: diff %.3g, tolerance %.3g)"
          % ((len(run["layers"]), len(failures)) + worst))
    return 1 if failures else 0

# ---------------------------------------------------------------- cases

AXES = ["z", "1,1,1", "0.3,-0.5,0.8"]
LAYERS = 30

def widths(vs):
    out = {}
    for name in AXES:
        d = parse_axis(name)
        hs = [dot(p, d) for p in vs]
        ext = max(hs) - min(hs)
        w = ext / LAYERS
        digits = -int(math.floor(math.log10(w))) + 1  # two significant digits
        out[name] = round(w, digits)
    return out

def punch(vs, fs, patches):
    """Remove the facets of each patch (lists of facet indices); returns the
    broken triangles and the record of what was removed."""
    gone = set()
    for p in patches:
        assert not gone & set(p), "patches overlap"
        gone |= set(p)
    kept = [f for k, f in enumerate(fs) if k not in gone]
    removed = [fs[k] for k in sorted(gone)]
    broken = tris_of(vs, kept)
    return broken, {"removed_facets": len(removed), "removed_tris": tris_of(vs, removed),
                    "removed_area": sum(tri_area(t) for t in tris_of(vs, removed)),
                    "patches": len(patches), "patch_sizes": [len(p) for p in patches],
                    "hole_edges": edge_counts(broken)["boundary_edges"]}

def quads(quad, keys):
    return [f for k in keys for f in quad[k]]

def case_sphere_holes():
    vs, fs, q = sphere()
    patches = [
        [q[(10, 5)][0]],                                              # one facet
        quads(q, [(30, j) for j in range(40, 45)]),                   # 10 facets
        quads(q, [(k, j) for k in range(5, 10) for j in range(50, 60)]),  # 100, near the top
        quads(q, [(k, j) for k in range(12, 37) for j in (30, 31)]),  # 100: a strip over most of the height
    ]
    broken, rec = punch(vs, fs, patches)
    return vs, fs, broken, rec

def case_torus_holes():
    vs, fs, q, _ = torus()
    patches = [
        [q[(5, 0)][0]],                                               # one facet, outer equator
        quads(q, [(i, 8) for i in range(30, 35)]),                    # 10 facets on the top
        quads(q, [(i, j) for i in range(60, 70) for j in range(14, 19)]),  # 100 on the inner side (saddle)
        quads(q, [(i, j % 32) for i in range(80, 83) for j in range(-8, 9)]),  # 102: outer half of the tube, bottom to top
    ]
    broken, rec = punch(vs, fs, patches)
    return vs, fs, broken, rec

def case_cube_open():
    vs, fs, named = cube()
    broken, rec = punch(vs, fs, [named["+x"]])  # a side face: every z layer is open
    return vs, fs, broken, rec

def case_sphere_flipped():
    vs, fs, _ = sphere()
    rng = random.Random(2401)
    flip = set(rng.sample(range(len(fs)), len(fs) * 3 // 20))  # 15%
    broken = tris_of(vs, [(a, c, b) if k in flip else (a, b, c) for k, (a, b, c) in enumerate(fs)])
    return vs, fs, broken, {"flipped": len(flip), "removed_area": 0.0}

def case_sphere_flipped_most():
    """60% of the facets flipped: the shell's majority is wound inward, so
    repair.h counts the 40% the file wound outward (the minority) and turns
    the shell outward as a whole."""
    vs, fs, _ = sphere()
    rng = random.Random(2404)
    flip = set(rng.sample(range(len(fs)), len(fs) * 3 // 5))
    broken = tris_of(vs, [(a, c, b) if k in flip else (a, b, c) for k, (a, b, c) in enumerate(fs)])
    return vs, fs, broken, {"flipped": len(fs) - len(flip), "removed_area": 0.0}

def case_torus_duplicates():
    vs, fs, _, _ = torus()
    rng = random.Random(2402)
    picks = rng.sample(range(len(fs)), 60)
    out = list(fs)
    for n, k in enumerate(picks):
        a, b, c = fs[k]
        # 40 exact copies, 15 with another first vertex, 5 wound the other way
        out.append((a, b, c) if n < 40 else (b, c, a) if n < 55 else (a, c, b))
    return vs, fs, tris_of(vs, out), {"duplicates": 60, "removed_area": 0.0}

def case_torus_crack():
    """Two halves (x > 0 and x < 0) of a torus written as unwelded copies:
    the x < 0 half's seam vertices moved by about 1e-9 of the model's size
    (the exact weld misses them; 1e-9 is well inside the 1e-6 of the box
    diagonal the tolerance weld joins)."""
    vs, fs, q, vid = torus()
    nmaj, nmin = 96, 32
    rng = random.Random(2403)
    seam = {vid(i, j) for i in (24, 72) for j in range(nmin)}
    moved = {}
    for s in sorted(seam):
        p = vs[s]
        moved[s] = tuple(c + rng.choice((-1, 1)) * 1e-9 * 28.0 for c in p)
    half_b = set(quads(q, [(i, j) for i in range(24, 72) for j in range(nmin)]))
    broken = []
    for k, f in enumerate(fs):
        if k in half_b:
            broken.append(tuple(moved.get(x, vs[x]) for x in f))
        else:
            broken.append(tuple(vs[x] for x in f))
    diag = norm(sub(tuple(max(p[i] for p in vs) for i in range(3)), tuple(min(p[i] for p in vs) for i in range(3))))
    gap = max(norm(sub(moved[s], vs[s])) for s in seam)
    assert gap < 1e-6 * diag / 100 and all(moved[s] != vs[s] for s in seam)
    return vs, fs, broken, {"seam_vertices": len(seam), "seam_gap": gap, "diagonal": diag,
                            "removed_area": 0.0, "hole_edges": edge_counts(broken)["boundary_edges"]}

CASES = {
    "sphere_holes": case_sphere_holes,
    "torus_holes": case_torus_holes,
    "cube_open": case_cube_open,
    "sphere_flipped": case_sphere_flipped,
    "sphere_flipped_most": case_sphere_flipped_most,
    "torus_duplicates": case_torus_duplicates,
    "torus_crack": case_torus_crack,
}

def generate(outdir):
    os.makedirs(outdir, exist_ok=True)
    manifest = {}
    for name, make in CASES.items():
        vs, fs, broken, rec = make()
        closed = tris_of(vs, fs)
        assert edge_counts(closed)["boundary_edges"] == 0
        write_stl_ascii(os.path.join(outdir, name + ".stl"), broken, name)
        write_stl_ascii(os.path.join(outdir, name + ".closed.stl"), closed, name + "_closed")
        write_stl_ascii(os.path.join(outdir, name + ".removed.stl"), rec.pop("removed_tris", []), name + "_removed")
        rec.update({"facets": len(broken), "closed_facets": len(closed), "widths": widths(vs)})
        for k in ("patches", "hole_edges", "flipped", "duplicates", "seam_vertices"):
            rec.setdefault(k, 0)
        manifest[name] = rec
    with open(os.path.join(outdir, "cases.json"), "w") as f:
        json.dump(manifest, f, indent=1, sort_keys=True)

# ---------------------------------------------------------------- PLY

def read_ply(src):
    """An ASCII PLY's vertex coordinates (as written: the text of x y z)
    and its faces (index lists)."""
    with open(src) as f:
        lines = iter(f.read().splitlines())
    assert next(lines).strip() == "ply"
    nv = nf = 0
    for line in lines:
        w = line.split()
        if w[:2] == ["format", "ascii"]:
            continue
        if w[:1] == ["format"]:
            raise SystemExit("ply2stl: only ASCII PLY")
        if w[:2] == ["element", "vertex"]:
            nv = int(w[2])
        elif w[:2] == ["element", "face"]:
            nf = int(w[2])
        elif w[:1] == ["end_header"]:
            break
    vs = [next(lines).split()[:3] for _ in range(nv)]
    faces = []
    for _ in range(nf):
        w = [int(x) for x in next(lines).split()]
        faces.append(w[1:1 + w[0]])
    return vs, faces

def ply_convert(src, dst):
    """To binary STL (triangles; polygons fanned) or, for .obj, to OBJ with
    the PLY's coordinates character for character (vertices no face uses
    left out)."""
    vs, faces = read_ply(src)
    used = sorted({i for f in faces for i in f})
    if dst.endswith(".obj"):
        new = {old: k + 1 for k, old in enumerate(used)}
        with open(dst, "w") as f:
            f.write("# %s: %d vertices, %d faces\n" % (os.path.basename(src), len(used), len(faces)))
            for i in used:
                f.write("v %s %s %s\n" % tuple(vs[i]))
            for face in faces:
                f.write("f %s\n" % " ".join(str(new[i]) for i in face))
    else:
        pos = [tuple(float(c) for c in v) for v in vs]
        tris = [(pos[f[0]], pos[f[k]], pos[f[k + 1]]) for f in faces for k in range(1, len(f) - 1)]
        write_stl_binary(dst, tris)
    print(json.dumps({"vertices": len(vs), "used_vertices": len(used), "faces": len(faces),
                      "triangles": sum(len(f) - 2 for f in faces)}))

# ---------------------------------------------------------------- main

def main(argv):
    if len(argv) >= 2 and argv[1] == "gen" and len(argv) == 3:
        generate(argv[2])
        return 0
    if len(argv) >= 4 and argv[1] == "check":
        tol, scale, removed = 0.0, 1.0, None
        rest = argv[4:]
        while rest:
            if rest[0] == "--tol-area":
                tol = float(rest[1])
            elif rest[0] == "--removed":
                removed = rest[1]
            elif rest[0] == "--scale":
                scale = float(rest[1])
            else:
                raise SystemExit("openmesh.py check: unknown option " + rest[0])
            rest = rest[2:]
        return check_run(argv[2], argv[3], tol, scale, removed)
    if len(argv) == 3 and argv[1] == "edges":
        print(json.dumps(edge_counts(read_stl(argv[2])), sort_keys=True))
        return 0
    if len(argv) >= 4 and argv[1] == "extent":
        tris = read_stl(argv[2])  # once for all the axes: a large mesh takes a while
        for ax in argv[3:]:
            d = parse_axis(ax)
            hs = [dot(p, d) for t in tris for p in t]
            print(json.dumps({"min": min(hs), "max": max(hs), "extent": max(hs) - min(hs)}))
        return 0
    if len(argv) == 4 and argv[1] == "ply2stl":
        ply_convert(argv[2], argv[3])
        return 0
    sys.stderr.write(__doc__)
    return 2

if __name__ == "__main__":
    sys.exit(main(sys.argv))
