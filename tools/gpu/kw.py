#!/usr/bin/env python3
"""On the GPU machine (tools/gpu/device_run.sh): Knotwork against the OCCT mesh peer, timed
alternately in one run, at the peer meshes tools/peer_search.py found on the 2-core machine.
Usage: kw.py PHASE...
  peer1024, peer4k, zoom8  edge reports of both (1024 only) and 3 alternating timing rounds
  modes, modes4k           Knotwork's frame time per KW_MODES (adaptive, uniform, aa4, ...)
  diag                     edge reports per KW_VARIANTS (renderer switches), models in KW_ONLY
Lines go to $OUT/res/results.txt; KW_FRAMES overrides the timed frames."""
import json
import os
import re
import statistics
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
K = os.environ.get("KW", "/opt/kw")
KW = K + "/bin/knotwork"
RES = os.path.join(os.environ["OUT"], "res")
os.makedirs(RES, exist_ok=True)
W = "/tmp/kwwork"; os.makedirs(W, exist_ok=True)
CAD = {"hammer": "tests/data/hammer.iges", "teapot": "tests/data/teapot.igs",
       "screw": "tests/data/screw.step", "Pump_Nut": "tests/data/Pump_Nut.brep",
       "Axis_of_bearing": "tests/data/Axis_of_bearing.brep", "Motor-c": K + "/data/Motor-c.brep"}
SIDE = {"hammer": 155.63 / 0.004, "teapot": 0.0261 / 0.004, "screw": 0.265927 / 0.004,
        "Pump_Nut": 0.24 / 0.004, "Axis_of_bearing": 0.52 / 0.004, "Motor-c": 0.836003 / 0.004}
# The peer meshes found by tools/peer_search.py on the 2-core machine (docs/PERFORMANCE.md, "The
# OpenCASCADE mesh peer"): (fraction of the side, angular degrees), and their triangles.
FIT = {"hammer": (0.000125, 2.5, 138729), "teapot": (6.25e-05, 2.5, 692876),
       "screw": (0.001, 5.0, 3224), "Pump_Nut": (0.001, 3.5355339, 43954),
       "Axis_of_bearing": (0.0005, 7.0710678, 92636), "Motor-c": (0.0005, 5.0, 137070)}
Z8 = {"hammer": (0.000125, 1.7677670, 279368), "screw": (0.004, 14.142136, 846),
      "Pump_Nut": (3.125e-05, 7.0710678, 50832), "teapot": (3.125e-05, 2.5, 806776),
      "Motor-c": (0.00025, 5.0, 149166)}

def log(name, line):
    print(line, flush=True)
    with open(os.path.join(RES, "results.txt"), "a") as f:
        f.write("[%s] %s\n" % (name, line))

def run(cmd, timeout=240):
    t = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if p.returncode != 0:
        raise RuntimeError("%s failed (%d): %s" % (" ".join(cmd), p.returncode, p.stderr[-800:]))
    return p.stdout + p.stderr, time.time() - t

def num(pat, text):
    m = re.search(pat, text)
    return float(m.group(1)) if m else None

def mesh(name, frac, ang, tris):
    obj = os.path.join(W, "%s_%g_%g.obj" % (name, frac, ang))
    knot = os.path.join(W, name + ".knot")
    if not os.path.exists(obj):
        out, sec = run([KW, "mesh", CAD[name], "-o", obj, "--linear-deflection", repr(frac * SIDE[name]),
                        "--angular-deflection", repr(ang), "--knot", knot], timeout=300)
        got = int(num(r"(\d+) triangles", out))
        log("mesh", "%s linear %.4g angular %g: %d triangles (2-core run: %d), %.1f s" %
            (name, frac * SIDE[name], ang, got, tris, sec))
    return knot, obj

def render(knot, size, extra, frames=0, tag="t"):
    png = os.path.join(W, "%s.png" % tag)
    cmd = [KW, "render", knot, "-o", png, "--size", size] + extra
    if frames:
        cmd += ["--time-frames", str(frames)]
    return run(cmd)[0]

def timed(knot, size, extra, frames):
    out = render(knot, size, extra, frames)
    return num(r"median frame ([\d.]+) ms", out), out

ONLY = os.environ.get("KW_ONLY")
FRAMES = int(os.environ.get("KW_FRAMES", "0"))

def compare(tag, table, size, zoom, frames, rounds=3, report=True):
    table = {n: v for n, v in table.items() if not ONLY or n in ONLY.split(",")}
    frames = FRAMES or frames
    with ThreadPoolExecutor(8) as ex:
        made = dict(zip(table, ex.map(lambda n: mesh(n, *table[n]), table)))
    for name in table:
        knot, obj = made[name]
        z = ["--zoom", str(zoom)] if zoom != 1 else []
        if report:
            for who, ex_ in (("knotwork", []), ("peer", ["--peer-mesh", obj])):
                rep = os.path.join(W, "%s_%s_%s.json" % (tag, name, who))
                render(knot, size, z + ex_ + ["--edge-report", rep], tag="%s_%s_%s" % (tag, name, who))
                q = json.load(open(rep))
                log(tag, "%s %s: silhouette max %.2f px, normal p99 %.4f deg, crack px %d (%d), id %d" %
                    (name, who, q["silhouetteMaxPixels"], q["normalP99Degrees"], q["crackPixels"],
                     q["crackPixelsCoveredInReference"], q["idDisagreements"]))
        kw, peer = [], []
        for _ in range(rounds):
            a, out_a = timed(knot, size, z, frames)
            b, out_b = timed(knot, size, z + ["--peer-mesh", obj], frames)
            kw.append(a); peer.append(b)
        cells = num(r"partitions: (\d+) cells", out_a)
        tris = num(r"peer mesh .*?: (\d+) triangles", out_b)
        k, p = statistics.median(kw), statistics.median(peer)
        log(tag, "| %s | %s | %dx | %d | %.3f | %d | %.3f | %.2fx | rounds kw %s peer %s" % (
            name, size, zoom, tris or -1, p, cells or -1, k, p / k,
            ",".join("%.3f" % x for x in kw), ",".join("%.3f" % x for x in peer)))

def modes(size, frames):
    frames = FRAMES or frames
    for name in [n for n in FIT if not ONLY or n in ONLY.split(",")]:
        knot, obj = mesh(name, *FIT[name])
        res = {}
        variants = {"adaptive": [], "uniform": ["--partition-mode", "uniform"],
                    "aa4": ["--samples", "4"],
                    "aa4cov": ["--samples", "4", "--aa-method", "coverage"],
                    "exactdepth": ["--depth", "exact-depth"],
                    "zebra": ["--shading", "zebra"], "notrims": ["--no-trims"]}
        keep = os.environ.get("KW_MODES")
        variants = {v: e for v, e in variants.items() if not keep or v in keep.split(",")}
        for r in range(3):
            for v, ex_ in variants.items():
                res.setdefault(v, []).append(timed(knot, size, ex_, frames)[0])
        med = {v: statistics.median(x) for v, x in res.items()}
        log("modes", "| %s | %s | " % (name, size) + " | ".join("%s %.3f" % (v, m) for v, m in med.items())
            + (" | adaptive/uniform %.2fx" % (med["adaptive"] / med["uniform"]) if "uniform" in med else ""))

def diag(models, variants, size="1024x1024", zoom=1):
    for name in models:
        knot, obj = mesh(name, *FIT[name])
        for tag, (env, extra) in variants.items():
            rep = os.path.join(W, "diag_%s_%s.json" % (name, tag))
            old = dict(os.environ); os.environ.update(env)
            try:
                z = ["--zoom", str(zoom)] if zoom != 1 else []
                render(knot, size, z + extra + ["--edge-report", rep], tag="diag_%s_%s" % (name, tag))
                q = json.load(open(rep))
                log("diag", "%s %s: silhouette max %.2f px, normal p99 %.4f deg, crack %d (%d), id %d, covered %d/%d" %
                    (name, tag, q["silhouetteMaxPixels"], q["normalP99Degrees"], q["crackPixels"],
                     q["crackPixelsCoveredInReference"], q["idDisagreements"], q["covered"], q["referenceCovered"]))
            except Exception as e:
                log("diag", "%s %s: FAILED %s" % (name, tag, str(e)[-300:]))
            finally:
                os.environ.clear(); os.environ.update(old)

VARIANTS = {
    "default": ({}, []), "noskirts": ({"KW_EDGE_SKIRTS": "0"}, []), "nofins": ({"KW_FINS": "0"}, []),
    "nomulti": ({"KW_MULTI_DRAW": "0"}, []), "nogather": ({"KW_GATHER_MIN_CELL_PX": "1e12"}, []),
    "allgather": ({"KW_GATHER_MIN_CELL_PX": "0"}, []), "nosplit": ({"KW_TRIM_CELL_SPLIT": "0"}, []),
    "uniform": ({}, ["--partition-mode", "uniform"]), "notrims": ({}, ["--no-trims"]),
    "exactdepth": ({}, ["--depth", "exact-depth"]), "tess": ({}, ["--mode", "tessellated"]),
    "maskmode": ({}, ["--trim-mode", "mask"]),
    "barenotrims": ({"KW_EDGE_SKIRTS": "0", "KW_FINS": "0", "KW_MULTI_DRAW": "0", "KW_GATHER_MIN_CELL_PX": "1e12",
              "KW_TRIM_CELL_SPLIT": "0"}, ["--partition-mode", "uniform", "--no-trims"]),
    "bare": ({"KW_EDGE_SKIRTS": "0", "KW_FINS": "0", "KW_MULTI_DRAW": "0", "KW_GATHER_MIN_CELL_PX": "1e12",
              "KW_TRIM_CELL_SPLIT": "0"}, ["--partition-mode", "uniform"]),
}


if __name__ == "__main__":
    for ph in sys.argv[1:]:
        t = time.time()
        try:
            if ph == "peer1024": compare("peer1024", FIT, "1024x1024", 1, 200)
            elif ph == "peer4k": compare("peer4k", FIT, "3840x2160", 1, 100, report=False)
            elif ph == "zoom8": compare("zoom8", Z8, "1024x1024", 8, 200)
            elif ph == "modes": modes("1024x1024", 200)
            elif ph == "modes4k": modes("3840x2160", 100)
            elif ph == "diag":
                keep = os.environ.get("KW_VARIANTS")
                diag([n for n in FIT if not ONLY or n in ONLY.split(",")],
                     {k: v for k, v in VARIANTS.items() if not keep or k in keep.split(",")})
            else:
                raise RuntimeError("unknown phase")
        except Exception as e:
            log("errors", "%s: %s" % (ph, e))
        log("phases", "%s %.1f s" % (ph, time.time() - t))
