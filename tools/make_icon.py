#!/usr/bin/env python3
"""Writes Knotwork's application icon, packaging/icons/knotwork.svg: a trefoil knot (over and
under at each crossing) over its dashed control polygon, on a rounded square. With --png it also
renders the PNG sizes the desktop wants into packaging/icons/SIZE/knotwork.png with rsvg-convert
(Debian: librsvg2-bin). Deterministic; edit this script, not the files. Standard library only.

    python3 tools/make_icon.py [--png]
"""
import math
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
ICONS = ROOT / "packaging" / "icons"
SIZES = (16, 24, 32, 48, 64, 128, 256, 512)
CENTRE, SCALE = 128.0, 30.0


def point(t):
    """The trefoil x = sin t + 2 sin 2t, y = cos t - 2 cos 2t, z = -sin 3t, in icon pixels."""
    x = math.sin(t) + 2.0 * math.sin(2.0 * t)
    y = math.cos(t) - 2.0 * math.cos(2.0 * t)
    # y spans [-3, 2.06]: shifted so that the knot sits in the middle of the square.
    return CENTRE + SCALE * x, CENTRE - SCALE * (y + 0.47), -math.sin(3.0 * t)


def path(t0, t1, steps):
    pts = [point(t0 + (t1 - t0) * k / steps) for k in range(steps + 1)]
    return "M" + " L".join(f"{x:.2f},{y:.2f}" for x, y, _ in pts)


def svg():
    full = path(0.0, 2.0 * math.pi, 360) + " Z"
    # The strand is over where z > 0: redraw the middle of those arcs (z > 0.35) with a dark
    # edge, so each crossing shows which strand passes over.
    overs = []
    for k in range(3):
        a = (2.0 * k + 1.0) * math.pi / 3.0  # -sin(3t) > 0 for t in (pi/3, 2pi/3) + 2k pi/3
        lo, hi = a + math.asin(0.35) / 3.0, a + (math.pi - math.asin(0.35)) / 3.0
        overs.append(path(lo, hi, 60))
    # The control polygon: the lobes' tips and the three inner turning points.
    ctrl = [point(k * math.pi / 3.0) for k in range(6)]
    poly = "M" + " L".join(f"{x:.2f},{y:.2f}" for x, y, _ in ctrl) + " Z"
    handles = "\n".join(
        f'  <rect x="{x - 6:.2f}" y="{y - 6:.2f}" width="12" height="12" rx="2" '
        f'fill="#f1faee" stroke="#1d3557" stroke-width="2"/>' for x, y, _ in ctrl)
    over = "\n".join(
        f'  <path d="{d}" fill="none" stroke="#12233a" stroke-width="30"/>\n'
        f'  <path d="{d}" fill="none" stroke="url(#strand)" stroke-width="20"/>' for d in overs)
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<!-- Knotwork's icon: a trefoil knot over its control polygon. Made by tools/make_icon.py. -->
<svg xmlns="http://www.w3.org/2000/svg" width="256" height="256" viewBox="0 0 256 256">
  <defs>
    <linearGradient id="back" x1="0" y1="0" x2="0" y2="1">
      <stop offset="0" stop-color="#2b5d8c"/>
      <stop offset="1" stop-color="#1d3557"/>
    </linearGradient>
    <linearGradient id="strand" gradientUnits="userSpaceOnUse" x1="40" y1="40" x2="216" y2="216">
      <stop offset="0" stop-color="#ffd166"/>
      <stop offset="1" stop-color="#f3722c"/>
    </linearGradient>
  </defs>
  <rect x="8" y="8" width="240" height="240" rx="48" fill="url(#back)"/>
  <path d="{poly}" fill="none" stroke="#a8dadc" stroke-width="3" stroke-dasharray="8 6"
        stroke-linejoin="round" opacity="0.8"/>
  <path d="{full}" fill="none" stroke="url(#strand)" stroke-width="20" stroke-linejoin="round"/>
{over}
{handles}
</svg>
"""


def main():
    ICONS.mkdir(parents=True, exist_ok=True)
    source = ICONS / "knotwork.svg"
    source.write_text(svg(), encoding="utf-8")
    if "--png" in sys.argv[1:]:
        for size in SIZES:
            out = ICONS / str(size) / "knotwork.png"
            out.parent.mkdir(exist_ok=True)
            subprocess.run(["rsvg-convert", "-w", str(size), "-h", str(size), "-o", str(out),
                            str(source)], check=True)


if __name__ == "__main__":
    main()
