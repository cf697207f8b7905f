#!/usr/bin/env python3
"""Classify pixels of an RGB(A) PNG (as rsvg-convert or chromium write it) as
'background' (white), 'material' (the sheet's blue fill), 'tint' (the light
fill of solids under scan paths, #c9dbf0) or 'other'.
usage: pixel.py FILE.png X,Y [X,Y ...]"""
import operator
import struct
import sys
import zlib


def decode_png(data):
    """an 8-bit RGB(A) PNG's bytes: (rows of bytearrays, bytes a pixel)"""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            assert depth == 8 and ctype in (2, 6), "expected 8-bit RGB or RGBA"
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    wrap = list(range(256)) * 2
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if f == 2:  # "up", what fast screenshots use: one C-level map
            line = bytearray(map(wrap.__getitem__, map(operator.add, line, prev)))
        elif f:
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                if f == 1:
                    line[i] = (line[i] + a) & 255
                elif f == 3:
                    line[i] = (line[i] + (a + b) // 2) & 255
                elif f == 4:
                    p = a + b - c
                    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                    pr = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                    line[i] = (line[i] + pr) & 255
        rows.append(line)
        prev = line
    return rows, bpp


def read_png(path):
    return decode_png(open(path, "rb").read())


def main():
    rows, bpp = read_png(sys.argv[1])
    out = []
    for arg in sys.argv[2:]:
        x, y = map(int, arg.split(","))
        r, g, b = rows[y][x * bpp:x * bpp + 3]
        if r > 240 and g > 240 and b > 240:
            out.append("background")
        elif b > 150 and r < 90 and g < 150:
            out.append("material")
        elif abs(r - 0xc9) <= 8 and abs(g - 0xdb) <= 8 and abs(b - 0xf0) <= 8:
            out.append("tint")
        else:
            out.append("other(%d,%d,%d)" % (r, g, b))
    print(" ".join(out))


if __name__ == "__main__":
    main()
