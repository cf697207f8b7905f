# partcraft.py IN OUT TAG FIELD VALUE: a copy of part file IN with one value
# changed and both its hashes made right again (the format of
# core/plan/part.h, read here on its own). TAG: C (the first contour: FIELD
# x|y|z of its first point, or power), H (the first hatch block: x|y|z of
# its first vector's start, or kind: made 9, no region), M (the
# first move: x|y|z), L (the first layer: z, its height), J (the header's
# job: zmax of its box), - (nothing: the hashes only). VALUE: a number,
# nan, inf, or hi+K / lo-K: the job's box on FIELD's axis, K beads beyond;
# - for kind.
# Prints the changed record's layer (the run's, from 1; - for the header)
# and its byte offset.
import struct, sys
src, dst, tag, field, value = sys.argv[1:6]
b = bytearray(open(src, "rb").read())
MASK, PRIME = (1 << 64) - 1, 0x100000001b3
def fnv(data):
    h = 0xcbf29ce484222325
    for x in data:
        h = ((h ^ x) * PRIME) & MASK
    return h
u64 = lambda o: struct.unpack_from("<Q", b, o)[0]
f64 = lambda o: struct.unpack_from("<d", b, o)[0]
assert b[:8] == b"LAMPART\0"
first = u64(24)                         # the part's first layer
o = 48                                  # magic, version, flags, 4 counts
for _ in range(4):                      # name, process, units, label
    o += 8 + u64(o)
job = o                                 # bbox[6] bead rate travel origin[3]
bbox = [f64(job + 8 * i) for i in range(6)]
bead = f64(job + 48)
o = job + 96
for _ in range(2):                      # profile, model
    o += 8 + u64(o)
nattrs = u64(o)                         # the attribute keys
o += 8
for _ in range(nattrs):
    o += 8 + u64(o)
A = 8 * nattrs                          # an attribute block
nlabels = u64(o)                        # a build's labels (version 3)
o += 8
for _ in range(nlabels):
    o += 8 + u64(o)
hhash = o
assert u64(hhash) == fnv(b[:hhash]), "the header's hash"
axis = {"x": 0, "y": 1, "z": 2}.get(field, 0)
if value.startswith("hi+"):
    v = bbox[axis + 3] + float(value[3:]) * bead
elif value.startswith("lo-"):
    v = bbox[axis] - float(value[3:]) * bead
elif value != "-":
    v = float(value)
o, layer, hit = hhash + 8, first - 1, None  # hit: (offset, layer, where the value is)
while chr(b[o]) != "Z":
    t, r = chr(b[o]), o + 1
    if t == "L":
        layer += 1
        n, at = 40, r + 8
    elif t == "E":
        n, at = 120, None
    elif t == "F":
        n, at = 8, None
    elif t == "A":
        n, at = 1, None
    elif t == "M":                      # attrs, deposit, xyz, uv
        n, at = A + 41, r + A + 1 + 8 * axis
    elif t == "C":                      # attrs, solid, depth, z, n, 4 exposure, has_uv
        q = r + A
        cnt, uv = u64(q + 17), b[q + 57]
        n, at = A + 58 + 8 * cnt * (5 if uv else 3), (q + 25 if field == "power" else q + 58 + 8 * axis)
    elif t == "H":                      # attrs, kind, z, n, angle, 4 exposure, has_uv
        q = r + A
        cnt, uv = u64(q + 16), b[q + 64]
        n, at = A + 65 + 8 * cnt * (10 if uv else 6), (q if field == "kind" else q + 65 + 8 * axis)
    else:
        raise SystemExit("unknown record %r at byte %d" % (t, o))
    if t == tag and hit is None:
        hit = (o, layer, at)
    o = r + n
end = o
assert len(b) == end + 9, "the part ends after its 'Z' record"
assert u64(end + 1) == fnv(b[:end + 1]), "the part's hash"
if tag == "J":  # (lamina names the box's offset, or the bead's)
    hit = (job + (48 if field == "bead" else 0), "-", job + {"zmax": 40, "bead": 48}[field])
if tag != "-":
    assert hit, "no such record"
    if field == "kind":
        struct.pack_into("<Q", b, hit[2], 9)
    else:
        struct.pack_into("<d", b, hit[2], v)
    struct.pack_into("<Q", b, hhash, fnv(b[:hhash]))
    print(hit[1], hit[0])
struct.pack_into("<Q", b, end + 1, fnv(b[:end + 1]))
open(dst, "wb").write(b)
