#!/usr/bin/env python3
"""Generate the projective-mapping demo images (no downloads, Python standard library only).

  tools/mapping-assets/make-mapping-assets.py [OUT_DIR]   (default: data/mappings)

Writes
  symbols.png     256x256 RGBA atlas of 2x2 cells (128 px each), transparent background:
                  (0,0) red warning triangle, (1,0) blue circle with a white cross (shelter),
                  (0,1) green square (camp), (1,1) orange diamond (viewpoint).
                  Cell (c, r) counts columns from the left and rows from the TOP of the image.
  focus-mask.png  128x128 RGBA white disc, alpha 1 inside radius 0.35, smooth to 0 at 0.5.
The output is deterministic: the same bytes on every run.
"""
import math
import os
import struct
import sys
import zlib


def write_png(path, width, height, pixels):
    """pixels: bytes of RGBA8, top row first."""
    raw = b"".join(b"\x00" + pixels[y * width * 4:(y + 1) * width * 4] for y in range(height))

    def chunk(tag, data):
        return (struct.pack(">I", len(data)) + tag + data +
                struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF))

    png = (b"\x89PNG\r\n\x1a\n" +
           chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    with open(path, "wb") as f:
        f.write(png)


def smooth(edge0, edge1, x):
    t = min(max((x - edge0) / (edge1 - edge0), 0.0), 1.0)
    return t * t * (3 - 2 * t)


def cover(inside_distance, aa=1.5):
    """Alpha from a signed distance in pixels (positive inside), anti-aliased."""
    return min(max(inside_distance / aa + 0.5, 0.0), 1.0)


def symbol(cell, x, y):
    """RGBA (0..1) of cell `cell` at local pixel centre (x, y) in [0, 128)."""
    cx, cy = 64.0, 64.0
    if cell == (0, 0):  # warning triangle, apex up
        # Distances to the three edges of an equilateral triangle with circumradius 52.
        r = 52.0
        d = []
        for k in range(3):
            a = math.radians(90 + 120 * k + 60)  # outward normals point between vertices
            nx, ny = math.cos(a), -math.sin(a)
            d.append(r * 0.5 - ((x - cx) * nx + (y - cy + 8) * ny))
        inside = min(d)
        a = cover(inside)
        inner = cover(inside - 10)
        col = (0.85, 0.1, 0.1) if inner < 0.5 else (1.0, 0.95, 0.9)
        return col + (a,)
    if cell == (1, 0):  # shelter: blue disc, white cross
        dist = math.hypot(x - cx, y - cy)
        a = cover(54 - dist)
        cross = abs(x - cx) < 9 and abs(y - cy) < 34 or abs(y - cy) < 9 and abs(x - cx) < 34
        return ((1.0, 1.0, 1.0) if cross else (0.1, 0.3, 0.85)) + (a,)
    if cell == (0, 1):  # camp: green square with a white border
        inside = 50 - max(abs(x - cx), abs(y - cy))
        a = cover(inside)
        return ((0.1, 0.6, 0.2) if inside > 6 else (1.0, 1.0, 1.0)) + (a,)
    # viewpoint: orange diamond
    inside = 54 - (abs(x - cx) + abs(y - cy))
    return (1.0, 0.55, 0.0) + (cover(inside),)


def to_bytes(rgba):
    return bytes(int(round(min(max(v, 0.0), 1.0) * 255)) for v in rgba)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "..", "data", "mappings")
    os.makedirs(out, exist_ok=True)
    n = 256
    px = bytearray()
    for y in range(n):
        for x in range(n):
            cell = (x // 128, y // 128)
            px += to_bytes(symbol(cell, x % 128 + 0.5, y % 128 + 0.5))
    write_png(os.path.join(out, "symbols.png"), n, n, bytes(px))
    m = 128
    px = bytearray()
    for y in range(m):
        for x in range(m):
            r = math.hypot((x + 0.5) / m - 0.5, (y + 0.5) / m - 0.5)
            px += to_bytes((1.0, 1.0, 1.0, 1.0 - smooth(0.35, 0.5, r)))
    write_png(os.path.join(out, "focus-mask.png"), m, m, bytes(px))


if __name__ == "__main__":
    main()
