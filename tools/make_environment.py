#!/usr/bin/env python3
"""Writes resources/environment/studio.png, the bundled default environment map of the
'environment' analysis mode: an equirectangular (longitude along x from -180 degrees, latitude
+90 at the top, z up) photo-studio-like image made procedurally: a soft grey-blue sky gradient,
a dark floor, a bright horizon band and four rectangular soft boxes, so reflections show
curvature flow clearly. Standard library only (zlib + struct PNG writer).

Usage: python3 tools/make_environment.py [OUT.png]   (default resources/environment/studio.png)
"""
import math
import os
import struct
import sys
import zlib

W, H = 512, 256

# Soft boxes: (centre longitude deg, centre latitude deg, half width deg, half height deg, rgb)
BOXES = [
    (-60.0, 35.0, 22.0, 10.0, (1.0, 0.98, 0.95)),
    (70.0, 20.0, 12.0, 25.0, (0.95, 0.97, 1.0)),
    (170.0, 45.0, 30.0, 6.0, (1.0, 1.0, 1.0)),
    (10.0, 70.0, 40.0, 8.0, (0.9, 0.92, 1.0)),
]


def smoothstep(e0, e1, x):
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


def pixel(lon, lat):
    if lat >= 0.0:  # sky: light at the horizon, deeper blue-grey at the zenith
        t = lat / 90.0
        c = [0.78 - 0.35 * t, 0.80 - 0.30 * t, 0.84 - 0.20 * t]
    else:  # floor: dark warm grey, darker downwards
        t = -lat / 90.0
        c = [0.22 - 0.12 * t, 0.20 - 0.11 * t, 0.19 - 0.10 * t]
    band = math.exp(-(lat / 3.0) ** 2)  # bright horizon line
    c = [x + 0.35 * band for x in c]
    for lon0, lat0, hw, hh, rgb in BOXES:
        dlon = (lon - lon0 + 180.0) % 360.0 - 180.0
        inside = (1.0 - smoothstep(hw - 2.0, hw + 2.0, abs(dlon))) * (
            1.0 - smoothstep(hh - 2.0, hh + 2.0, abs(lat - lat0)))
        c = [x * (1.0 - inside) + y * inside for x, y in zip(c, rgb)]
    return [int(round(255.0 * min(max(x, 0.0), 1.0))) for x in c]


def write_png(path, rows):
    raw = b"".join(b"\x00" + bytes(r) for r in rows)

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))

    png = (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", W, H, 8, 2, 0, 0, 0)) +
           chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(png)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)  # write-then-rename


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "resources", "environment", "studio.png")
    rows = []
    for y in range(H):
        lat = 90.0 - (y + 0.5) * 180.0 / H
        row = []
        for x in range(W):
            lon = -180.0 + (x + 0.5) * 360.0 / W
            row.extend(pixel(lon, lat))
        rows.append(row)
    write_png(out, rows)
    print(f"wrote {out} ({W}x{H})")


if __name__ == "__main__":
    main()
