#!/usr/bin/env python3
"""Independent reader of binary Common Layer Interface files (layers 127,
polylines 130, hatches 132), printing the same text the cli-ascii profile
writes, so a test can compare the two.
usage: clidecode.py FILE.cli"""
import struct
import sys

def num(v):
    """%.5f without a negative zero, as lamina's ASCII writer"""
    s = "%.5f" % v
    return "0.00000" if s == "-0.00000" else s

data = open(sys.argv[1], "rb").read()
end = data.index(b"$$HEADEREND") + len(b"$$HEADEREND")
header = data[:end].decode("ascii").split("\n")
assert header[0] == "$$HEADERSTART" and "$$BINARY" in header, "not a binary CLI header"
def field(name):
    found = [h for h in header if h.startswith(name + "/")]
    return found[0] if found else None
lines = ["$$HEADERSTART", "$$ASCII", "$$UNITS/1", "$$VERSION/200"]
lines += [h for h in (field("$$DIMENSION"), field("$$LAYERS"), field("$$LABEL")) if h]
print("\n".join(lines + ["$$HEADEREND", "$$GEOMETRYSTART"]))
pos = end
while pos < len(data):
    (cmd,) = struct.unpack_from("<H", data, pos)
    pos += 2
    if cmd == 127:
        (z,) = struct.unpack_from("<f", data, pos)
        pos += 4
        print("$$LAYER/%s" % num(z))
    elif cmd == 130:
        pid, pdir, n = struct.unpack_from("<iii", data, pos)
        pos += 12
        xy = struct.unpack_from("<%df" % (2 * n), data, pos)
        pos += 8 * n
        print("$$POLYLINE/%d,%d,%d,%s" % (pid, pdir, n, ",".join(num(v) for v in xy)))
    elif cmd == 132:
        pid, n = struct.unpack_from("<ii", data, pos)
        pos += 8
        xy = struct.unpack_from("<%df" % (4 * n), data, pos)
        pos += 16 * n
        print("$$HATCHES/%d,%d,%s" % (pid, n, ",".join(num(v) for v in xy)))
    else:
        sys.exit("unknown command %d at byte %d" % (cmd, pos - 2))
print("$$GEOMETRYEND")
