#!/usr/bin/env python3
"""Pinhole sweep: render many random views of closed solids and count crack pixels.

Each file is converted once ('knotwork convert'), then rendered from VIEWS random orientations
and zooms (a camera fitted to the control bounds from a random direction, then
'--zoom F@X,Y' with F in 1..4 about a random point of the middle of the image) at SIZE x SIZE
with '--edge-report', which compares the GPU frame with the CPU reference
(render/edge_metrics.h). Per view it records:
  cracks     background pixels in runs of <= 2 px between covered pixels (GPU frame alone)
  covered    those of them the CPU reference covers (a real pinhole, not a gap in the part)
  sil_max    the farthest pixel (px) covered in one frame only from the reference silhouette
             (> 1.5: a lone pixel outside the one-pixel band)
Views with cracks or sil_max > 1.5 are kept as .knot files (with their --zoom in the name) in
--keep so that each can be rendered again alone. Prints a Markdown table.

With back faces of closed solids skipped (the default) a seam's sub-pixel gap between two faces'
exact trims shows the background where the reference sees the solid's inside through it;
--back-faces draws them, to tell those holes from any other.

Needs a display: run under xvfb-run -a -s "-screen 0 1280x1024x24" with QT_QPA_PLATFORM=xcb
(tools/dev.sh does). Deterministic for a given --seed.

  tools/pinhole_sweep.py --knotwork build/bin/knotwork --views 50 tests/data/Pump_Nut.brep ...
"""
import argparse
import json
import math
import os
import random
import subprocess
import sys
import tempfile


def control_bounds(scene):
    lo = [math.inf] * 3
    hi = [-math.inf] * 3
    for s in scene["surfaces"]:
        for p in s["points"]:
            for k in range(3):
                lo[k] = min(lo[k], p[k])
                hi[k] = max(hi[k], p[k])
    return lo, hi


def random_unit(rng):
    while True:
        v = [rng.uniform(-1.0, 1.0) for _ in range(3)]
        n = math.sqrt(sum(c * c for c in v))
        if 1e-3 < n <= 1.0:
            return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def random_view(rng, lo, hi, fov):
    """A camera looking at the bounds' centre from a random direction, the bounding sphere
    filling the view, a random roll; and a --zoom argument (F@X,Y)."""
    centre = [(a + b) * 0.5 for a, b in zip(lo, hi)]
    radius = 0.5 * math.sqrt(sum((b - a) ** 2 for a, b in zip(lo, hi)))
    d = random_unit(rng)
    dist = radius / math.sin(math.radians(fov) * 0.5)
    eye = [c + dist * k for c, k in zip(centre, d)]
    up = cross(d, random_unit(rng))
    n = math.sqrt(sum(c * c for c in up)) or 1.0
    up = [c / n for c in up]
    factor = rng.choice([1.0, 1.0, rng.uniform(1.0, 4.0)])
    x, y = rng.uniform(0.3, 0.7), rng.uniform(0.3, 0.7)
    zoom = "1" if factor == 1.0 else "%.4f@%.4f,%.4f" % (factor, x, y)
    return {"eye": eye, "target": centre, "up": up, "fovYDegrees": fov}, zoom


def render(knotwork, knot, size, zoom, report, env):
    cmd = [knotwork, "render", knot, "-o", report + ".png", "--size", "%dx%d" % (size, size),
           "--edge-report", report]
    if zoom != "1":
        cmd += ["--zoom", zoom]
    r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s: %s" % (" ".join(cmd), r.stderr.strip()))
    with open(report) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("files", nargs="+", help="closed solids (.brep, .step, .iges, .knot)")
    ap.add_argument("--knotwork", default="build/bin/knotwork")
    ap.add_argument("--views", type=int, default=50)
    ap.add_argument("--size", type=int, default=768)
    ap.add_argument("--seed", type=int, default=43)
    ap.add_argument("--keep", default="pinhole_views", help="folder for the views that crack")
    ap.add_argument("--back-faces", action="store_true",
                    help="draw closed solids' back faces too (KW_BACK_FACES=1): seam gaps then "
                         "show the solid's inside, as the reference does")
    args = ap.parse_args()
    env = dict(os.environ)
    env.setdefault("QT_QPA_PLATFORM", "xcb")
    if args.back_faces:
        env["KW_BACK_FACES"] = "1"
    os.makedirs(args.keep, exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for path in args.files:
            name = os.path.splitext(os.path.basename(path))[0]
            knot = os.path.join(tmp, name + ".knot")
            if path.endswith(".knot"):
                with open(path) as f:
                    scene = json.load(f)
            else:
                r = subprocess.run([args.knotwork, "convert", path, knot], env=env,
                                   stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                if r.returncode != 0:
                    print("%s: cannot convert: %s" % (path, r.stderr.strip()), file=sys.stderr)
                    return 1
                with open(knot) as f:
                    scene = json.load(f)
            lo, hi = control_bounds(scene)
            rng = random.Random("%d:%s" % (args.seed, name))
            total = {"cracks": 0, "covered": 0, "views_cracking": 0, "sil_bad": 0, "sil_max": 0.0}
            for v in range(args.views):
                camera, zoom = random_view(rng, lo, hi, 35.0)
                scene["camera"] = camera
                view = os.path.join(tmp, "%s_%02d.knot" % (name, v))
                with open(view, "w") as f:
                    json.dump(scene, f)
                m = render(args.knotwork, view, args.size, zoom, view + ".json", env)
                cracks, covered = m["crackPixels"], m["crackPixelsCoveredInReference"]
                sil = m["silhouetteMaxPixels"]
                total["cracks"] += cracks
                total["covered"] += covered
                total["sil_max"] = max(total["sil_max"], sil)
                bad = cracks > 0 or sil > 1.5
                total["views_cracking"] += cracks > 0
                total["sil_bad"] += sil > 1.5
                print("%s view %02d zoom %s: %d crack px (%d the reference covers), silhouette "
                      "max %.2f px" % (name, v, zoom, cracks, covered, sil), flush=True)
                if bad:
                    keep = os.path.join(args.keep, "%s_%02d_zoom_%s.knot" %
                                        (name, v, zoom.replace("@", "_at_").replace(",", "_")))
                    os.replace(view, keep)
            rows.append((name, total))
    print("\n| solid | views | crack px | of them covered in the reference | views with cracks "
          "| views with a silhouette pixel > 1.5 px off | worst silhouette px |")
    print("|---|---|---|---|---|---|---|")
    for name, t in rows:
        print("| %s | %d | %d | %d | %d | %d | %.2f |" % (name, args.views, t["cracks"],
                                                       t["covered"], t["views_cracking"],
                                                       t["sil_bad"], t["sil_max"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
