#!/usr/bin/env bash
# validate on open meshes (issue 24, item 4): a program sliced with
# --allow-open --no-repair from a sphere with a patch of facets punched out
# drops the sphere's outline wherever the plane crosses the hole; validate
# checks it against the repaired model and must say so (exit 3), along z
# and along oblique axes, naming layers in the hole's height range with the
# area lost. The areas are checked against the test's own sections of the
# closed original (plane/triangle intersection and the shoelace sum, below),
# not against lamina's. A model that stays open even after repair (a
# Moebius band) is said to be unverified instead of compared.
. "$(dirname "$0")/lib.sh"

D="$TMP/open models"
mkdir -p "$D"
cat >"$TMP/spheres.py" <<'EOF'
"""Two spheres (A: r 10 at the origin, B: r 8 at (25, 0, 0), separate
shells) and the same with A's facets within 25 degrees of +x removed.

  spheres.py write DIR            closed.stl, open.stl, moebius.stl in DIR
  spheres.py sections DIR AXIS    reads validate --json on stdin; one line per
                                  layer: index h A(h) B(h) seg(h) in_hole
A(h), B(h): each sphere's closed section at height h along AXIS (unit);
seg(h): the area between the section's missing part (the removed facets'
segments) and the chord across it, what a flat fill takes off A(h);
in_hole: 1 when the plane crosses a removed facet."""
import json, math, os, struct, sys

def sphere(c, r, nu, nv):
    V = [(c[0], c[1], c[2] + r)]
    for j in range(1, nv):
        th = math.pi * j / nv
        for i in range(nu):
            ph = 2 * math.pi * i / nu
            V.append((c[0] + r * math.sin(th) * math.cos(ph), c[1] + r * math.sin(th) * math.sin(ph),
                      c[2] + r * math.cos(th)))
    V.append((c[0], c[1], c[2] - r))
    ring = lambda j, i: 1 + (j - 1) * nu + i % nu
    T = [(0, ring(1, i), ring(1, i + 1)) for i in range(nu)]
    for j in range(1, nv - 1):
        for i in range(nu):
            a, b, cc, d = ring(j, i), ring(j + 1, i), ring(j + 1, i + 1), ring(j, i + 1)
            T += [(a, b, cc), (a, cc, d)]
    T += [(ring(nv - 1, i), len(V) - 1, ring(nv - 1, i + 1)) for i in range(nu)]
    return V, T

def punched(V, T, c, axis, deg):
    keep, gone = [], []
    for t in T:
        p = [sum(V[k][i] for k in t) / 3 - c[i] for i in range(3)]
        cos = sum(p[i] * axis[i] for i in range(3)) / math.sqrt(sum(x * x for x in p))
        (gone if cos > math.cos(math.radians(deg)) else keep).append(t)
    return keep, gone

def model():
    VA, TA = sphere((0, 0, 0), 10, 48, 24)
    VB, TB = sphere((25, 0, 0), 8, 32, 16)
    keep, gone = punched(VA, TA, (0, 0, 0), (1, 0, 0), 25)
    return VA, TA, keep, gone, VB, TB

def write_stl(path, parts):
    tris = [[V[k] for k in t] for V, T in parts for t in T]
    with open(path, 'wb') as f:
        f.write(b'\0' * 80 + struct.pack('<I', len(tris)))
        for t in tris:
            f.write(struct.pack('<3f', 0, 0, 0) + b''.join(struct.pack('<3f', *p) for p in t) + b'\0\0')

def moebius():
    V, T, n, R, w = [], [], 40, 5.0, 1.5
    for i in range(n):
        t = 2 * math.pi * i / n
        for s in (-w, w):
            V.append(((R + s * math.cos(t / 2)) * math.cos(t), (R + s * math.cos(t / 2)) * math.sin(t),
                      s * math.sin(t / 2)))
    for i in range(n):
        a, b = 2 * i, 2 * i + 1
        c, d = (2 * i + 2, 2 * i + 3) if i + 1 < n else (1, 0)  # the half twist
        T += [(a, b, d), (a, d, c)]
    return V, T

def segments(V, T, w, h):
    """Each triangle's segment in the plane p.w = h: (P, Q, key of P's edge,
    key of Q's edge), P where the boundary goes from above to below."""
    out = []
    for t in T:
        s = [sum(V[k][i] * w[i] for i in range(3)) - h for k in t]
        pts = {}
        for e in range(3):
            a, b = t[e], t[(e + 1) % 3]
            sa, sb = s[e], s[(e + 1) % 3]
            if (sa > 0) != (sb > 0):
                u = sa / (sa - sb)
                p = tuple(V[a][i] + u * (V[b][i] - V[a][i]) for i in range(3))
                pts['down' if sa > 0 else 'up'] = (p, (min(a, b), max(a, b)))
        if pts:
            out.append((pts['down'][0], pts['up'][0], pts['down'][1], pts['up'][1]))
    return out

def cross_w(p, q, w):
    return ((p[1] * q[2] - p[2] * q[1]) * w[0] + (p[2] * q[0] - p[0] * q[2]) * w[1] +
            (p[0] * q[1] - p[1] * q[0]) * w[2])

def shoelace(segs, w):
    """The area the segments enclose: the shoelace sum over them, 1/2 sum
    (P x Q).w (Green's theorem; they need not be chained)."""
    return abs(sum(cross_w(p, q, w) for p, q, _, _ in segs) / 2)

def hole_segment(segs, w):
    """The removed facets' segments form chains X ... Y (more than one where
    the plane crosses the punched patch's jagged edge twice); each closed by
    its chord Y -> X encloses what a flat fill cuts off the section there."""
    after = {kp: (p, q, kq) for p, q, kp, kq in segs}
    ends = {kq for _, _, _, kq in segs}
    total = 0.0
    for k in [kp for _, _, kp, _ in segs if kp not in ends]:
        x, twice = after[k][0], 0.0
        while k in after:
            p, q, k = after.pop(k)
            twice += cross_w(p, q, w)
        total += abs(twice + cross_w(q, x, w)) / 2
    return total if not after else float('nan')  # a closed loop of removed facets: not a hole's chain

def hollow():
    """A sphere r 10 with a cavity r 5 (wound inward), the cavity's facets
    within 40 degrees of +x removed: the cavity's outline drops where the
    plane crosses that hole, and the layer is solid where the part is not."""
    VO, TO = sphere((0, 0, 0), 10, 48, 24)
    VI, TI = sphere((0, 0, 0), 5, 48, 24)
    TI = [(a, c, b) for a, b, c in TI]
    keep, gone = punched(VI, TI, (0, 0, 0), (1, 0, 0), 40)
    return VO, TO, VI, TI, keep, gone

def main():
    if sys.argv[1] == 'write':
        d = sys.argv[2]
        VA, TA, keep, gone, VB, TB = model()
        write_stl(os.path.join(d, 'closed.stl'), [(VA, TA), (VB, TB)])
        write_stl(os.path.join(d, 'open.stl'), [(VA, keep), (VB, TB)])
        write_stl(os.path.join(d, 'moebius.stl'), [(VB, TB), moebius()])
        VO, TO, VI, TI, keep, gone = hollow()
        write_stl(os.path.join(d, 'hollow.stl'), [(VO, TO), (VI, keep)])
        return
    if sys.argv[1] == 'hollow':  # index h inner(h) seg(h) in_hole, along z
        VO, TO, VI, TI, keep, gone = hollow()
        w = [0, 0, 1]
        hs = [VI[k][2] for t in gone for k in t]
        for layer in json.load(sys.stdin)['layers']:
            h = layer['z']
            print(layer['index'], repr(h), repr(shoelace(segments(VI, TI, w, h), w)),
                  repr(hole_segment(segments(VI, gone, w, h), w)), int(min(hs) < h < max(hs)))
        return
    axis = [float(x) for x in {'z': '0,0,1'}.get(sys.argv[3], sys.argv[3]).split(',')]
    n = math.sqrt(sum(x * x for x in axis))
    w = [x / n for x in axis]
    VA, TA, keep, gone, VB, TB = model()
    hs = [sum(VA[k][i] * w[i] for i in range(3)) for t in gone for k in t]
    lo, hi = min(hs), max(hs)
    for layer in json.load(sys.stdin)['layers']:
        h = layer['z']
        a = shoelace(segments(VA, TA, w, h), w)
        b = shoelace(segments(VB, TB, w, h), w)
        seg = hole_segment(segments(VA, gone, w, h), w)
        print(layer['index'], repr(h), repr(a), repr(b), repr(seg), int(lo < h < hi))

main()
EOF
python3 "$TMP/spheres.py" write "$D"
closed="$D/closed.stl" open="$D/open.stl"

# Checks one axis's run of validate --json (file $1) against the test's
# sections (file $2): prints "ok" or what is wrong. Reported layers: each
# crosses the hole, holds B's section alone (A's outline dropped), and
# loses A(h) less what the fill takes off it, within 1% of A(h) or the
# filled hole's own area, whichever is larger; every layer that crosses
# the hole well inside it (1 from its ends) is reported; the layers that
# do not cross it compare exactly (net area within 1e-6 of A + B).
cat >"$TMP/judge.py" <<'EOF'
import json, sys
run = json.load(open(sys.argv[1]))
ref = {}
for line in open(sys.argv[2]):
    i, h, a, b, seg, inside = line.split()
    ref[int(i)] = (float(h), float(a), float(b), float(seg), inside == '1')
lo = min(h for h, a, b, s, inside in ref.values() if inside)
hi = max(h for h, a, b, s, inside in ref.values() if inside)
bad, reported = [], 0
for L in run['layers']:
    h, a, b, seg, inside = ref[L['index']]
    if not L['area_ok']:
        reported += 1
        if not inside:
            bad.append('layer %d (h=%g) reported but the plane misses the hole' % (L['index'] + 1, h))
        if abs(L['net_area'] - b) > 1e-6 * b:
            bad.append('layer %d: net area %r, not B alone (%r)' % (L['index'] + 1, L['net_area'], b))
        want = a - seg
        if not abs(L['area_lost'] - want) <= max(0.01 * a, seg):
            bad.append('layer %d: lost %r, the test expects %r (A %r less the fill %r)' %
                       (L['index'] + 1, L['area_lost'], want, a, seg))
    elif inside and lo + 1 < h < hi - 1:
        bad.append('layer %d (h=%g) crosses the hole but is not reported' % (L['index'] + 1, h))
    elif not inside and abs(L['net_area'] - (a + b)) > 1e-6 * (a + b):
        bad.append('layer %d (h=%g) away from the hole: net area %r, the test has %r' %
                   (L['index'] + 1, h, L['net_area'], a + b))
lost = sum(L['area_lost'] for L in run['layers'] if not L['area_ok'])
if not reported:
    bad.append('no layer reported')
if run['areas_lost'] != reported or abs(run['area_lost'] - lost) > 1e-9 * lost:
    bad.append('totals %r layers, %r lost; the layers say %d, %r' % (run['areas_lost'], run['area_lost'], reported, lost))
print('\n'.join(bad) if bad else 'ok %d' % reported)
EOF

for axis in z 1,1,1 0.3,-0.5,0.8; do
    run "$LAMINA" validate "$open" -a $axis -w 0.5 --allow-open --no-repair --json
    is "$RC" 3 "open sphere along $axis, --allow-open --no-repair: exit 3"
    printf '%s' "$OUT" >"$TMP/run.json"
    python3 "$TMP/spheres.py" sections "$D" $axis <"$TMP/run.json" >"$TMP/ref.txt"
    verdict=$(python3 "$TMP/judge.py" "$TMP/run.json" "$TMP/ref.txt")
    like "$verdict" '^ok [0-9]+$' "... the layers reported cross the hole, each losing A's section less the fill"
    [ "${verdict#ok}" = "$verdict" ] && echo "$verdict" | head -5 | sed 's/^/# /'
    like "$ERR" 'checked against a repaired copy: filled 1 hole' "... checked against the repaired copy, said on stderr"

    # the text: a layer in the hole's range named with its loss, the total
    first=$(jq -r '[.layers[] | select(.area_ok | not)][0] | "\(.index + 1) \(.z)"' "$TMP/run.json")
    read -r n h <<<"$first"
    in_range=$(awk -v h="$h" '$6 == 1 { if (lo == "" || $2 < lo) lo = $2; if (hi == "" || $2 > hi) hi = $2 }
                              END { print (h >= lo && h <= hi) ? 1 : 0 }' "$TMP/ref.txt")
    is "$in_range" 1 "... its first layer reported (layer $n, h=$h) is in the hole's height range"
    run "$LAMINA" validate "$open" -a $axis -w 0.5 --allow-open --no-repair -q
    is "$RC" 3 "... text: exit 3"
    like "$OUT" "^layer $n \\(h=[-0-9.e]+\\): [0-9]+ contours?, [0-9]+ confirmed, 0 disagreeing\$" "... text names layer $n"
    like "$OUT" "^  net area [0-9.e]+ \\(solids minus holes\\) but the model's section has [0-9.e]+: off by -[0-9.e]+ \\(lost [0-9.e]+, [0-9.]+% of the section\\), tolerance [0-9.e]+ \\(net area against the model's section, allowing for gap closing\\)\$" \
        "... with the area lost and its share of the section"
    like "$OUT" "; net area against the section in [0-9]+ layers \\([0-9]+ allowing for gap closing\\), [0-9]+ differ: [0-9.e+]+ lost in [0-9]+ layers \\([0-9.]+% of their sections\\)\$" \
        "... and the summary says how much was lost in all"

    # the closed original and the open one repaired on load lose nothing
    run "$LAMINA" validate "$closed" -a $axis -w 0.5 --json
    is "$RC" 0 "closed spheres along $axis: exit 0"
    is "$(jq -c '[.areas_compared == (.layers | length), .areas_differing, .areas_loss_checked, .areas_not_compared]' <<<"$OUT")" \
        "[true,0,0,0]" "... every layer's area compared exactly, none differ"
    run "$LAMINA" validate "$open" -a $axis -w 0.5 --json
    is "$RC" 0 "open spheres along $axis repaired on load: exit 0 (the fill holds the area)"
    is "$(jq -c '[.areas_compared == (.layers | length), .areas_differing, .open_outlines]' <<<"$OUT")" \
        "[true,0,0]" "... every area compared, none differ, no open outline"
done

# The lost area is the same read back from the program sliced the same way
# (the program does not say which layers bridged gaps: each is compared by
# the loss check), and a program sliced from the repaired model passes.
"$LAMINA" slice "$open" -w 0.5 --allow-open --no-repair -m cli-ascii -o "$TMP/open.cli" 2>/dev/null
run "$LAMINA" validate "$open" -w 0.5 --allow-open --no-repair -m cli-ascii --program "$TMP/open.cli" --json
is "$RC" 3 "the program sliced --allow-open --no-repair, read back: exit 3"
printf '%s' "$OUT" >"$TMP/prog.json"
python3 "$TMP/spheres.py" sections "$D" z <"$TMP/prog.json" >"$TMP/prog.txt"
verdict=$(python3 "$TMP/judge.py" "$TMP/prog.json" "$TMP/prog.txt")
like "$verdict" '^ok [0-9]+$' "... the same layers lose the same area, as the test has it"
[ "${verdict#ok}" = "$verdict" ] && echo "$verdict" | head -5 | sed 's/^/# /'
is "$(jq '.areas_loss_checked == (.layers | length)' <<<"$OUT")" true "... every layer read back compared by the loss check"
"$LAMINA" slice "$open" -w 0.5 -m cli-ascii -o "$TMP/repaired.cli" 2>/dev/null
run "$LAMINA" validate "$open" -w 0.5 -m cli-ascii --program "$TMP/repaired.cli"
is "$RC" 0 "the program sliced from the repaired model passes"
like "$OUT" ' 0 disagreeing; net area against the section in 40 layers, 0 differ$' "... every area compared, none differ"

# The same on any number of threads, and from standard input.
"$LAMINA" validate "$open" -a 1,1,1 -w 0.5 --allow-open --no-repair --json -j 1 >"$TMP/j1.json" 2>/dev/null
"$LAMINA" validate "$open" -a 1,1,1 -w 0.5 --allow-open --no-repair --json -j 3 >"$TMP/j3.json" 2>/dev/null
cmp -s "$TMP/j1.json" "$TMP/j3.json"
ok $? "the open spheres along 1,1,1: -j 3 reports what -j 1 does, byte for byte"
run "$LAMINA" validate - -a 1,1,1 -w 0.5 --allow-open --no-repair --json <"$open"
is "$RC" 3 "... from standard input: exit 3"
is "$(jq -c '[.areas_lost, .area_lost]' <<<"$OUT")" "$(jq -c '[.areas_lost, .area_lost]' "$TMP/j1.json")" \
    "... the same layers and area lost as from the file"

# A cavity punched: where its outline is dropped the layer is solid across
# the void, so the program holds more than the model: the cavity's section
# less what the fill takes off it (the test's own, as above).
hollow="$D/hollow.stl"
run "$LAMINA" validate "$hollow" -w 0.5 --allow-open --no-repair --json
is "$RC" 3 "a hollow sphere, its cavity punched, --allow-open --no-repair: exit 3"
printf '%s' "$OUT" >"$TMP/hollow.json"
python3 "$TMP/spheres.py" hollow <"$TMP/hollow.json" >"$TMP/hollow.txt"
cat >"$TMP/judge_hollow.py" <<'EOF'
import json, sys
run = json.load(open(sys.argv[1]))
ref = {int(l.split()[0]): [float(x) for x in l.split()[1:]] for l in open(sys.argv[2])}
bad, n = [], 0
for L in run['layers']:
    h, inner, seg, inside = ref[L['index']]
    if L['area_ok']:
        continue
    n += 1
    want = -(inner - seg)
    if not inside or not abs(L['area_lost'] - want) <= max(0.01 * inner, seg):
        bad.append('layer %d (h=%g): area_lost %r, the test expects %r' % (L['index'] + 1, h, L['area_lost'], want))
if not n or run['areas_added'] != n or run['areas_lost'] != 0:
    bad.append('%d layers reported, %r added, %r lost' % (n, run['areas_added'], run['areas_lost']))
print('\n'.join(bad) if bad else 'ok %d' % n)
EOF
verdict=$(python3 "$TMP/judge_hollow.py" "$TMP/hollow.json" "$TMP/hollow.txt")
like "$verdict" '^ok [0-9]+$' "... each layer reported crosses the hole and holds the cavity's section more than the model"
[ "${verdict#ok}" = "$verdict" ] && echo "$verdict" | head -5 | sed 's/^/# /'
run "$LAMINA" validate "$hollow" -w 0.5 --allow-open --no-repair -q
like "$OUT" 'off by [0-9.e+]+ \([0-9.e+]+ more than the model has, [0-9.]+% of the section\)' "... text: more than the model has"
like "$OUT" '[0-9]+ differ: [0-9.e+]+ more than the model has in [0-9]+ layers$' "... and the summary says how much more"

# Repair cannot close a Moebius band (one side, one edge): its section means
# nothing, so no area is compared, and validate says so on stdout, in the
# JSON and on stderr; the sphere's contours beside it are still checked and
# agree, so the exit status is theirs (0).
mb="$D/moebius.stl"
run "$LAMINA" validate "$mb" -w 0.5 --allow-open -q
is "$RC" 0 "Moebius band beside a sphere: exit 0 (every contour checked agrees)"
like "$OUT" '^.*moebius\.stl: 32 layers, [1-9][0-9]* contours checked, [0-9]+ confirmed, 0 disagreeing; net area not compared: the model stays open \(80 boundary edges, 1 edge that cannot be oriented after repair\)$' \
    "... the summary says the area was not compared, and why"
like "$ERR" 'warning: .*moebius\.stl: net area not compared on 32 layers: the model stays open .*; the program.s area is not verified' \
    "... and a warning says so on stderr, even with -q"
run "$LAMINA" validate "$mb" -w 0.5 --allow-open --no-repair --json
is "$RC" 0 "... with --no-repair too (the repaired copy stays open): exit 0"
is "$(jq -c '[.areas_compared, .areas_differing, .areas_not_compared == (.layers | length)]' <<<"$OUT")" "[0,0,true]" \
    "... JSON: no area compared, every layer not compared"
like "$(jq -r .areas_not_compared_why <<<"$OUT")" '^the model stays open \(80 boundary edges' "... and why"
is "$(jq '([.layers[] | select(.area_ok and .area_lost == null)] | length) == (.layers | length)' <<<"$OUT")" true \
    "... each layer: no area lost given where none was compared"

done_testing
