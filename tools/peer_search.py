#!/usr/bin/env python3
"""The OpenCASCADE mesh peer (docs/PERFORMANCE.md ## Edges).

For each CAD file: convert it, render Knotwork (adaptive, the default) with --edge-report, then
mesh the file with BRepMesh (`knotwork mesh`) at decreasing deflections until the mesh drawn
with the baseline shader (`render --peer-mesh`) is as good on screen: normal error p99 and
silhouette max no worse than Knotwork's (or the finest step is reached). The mesh found is then
relaxed one step in each deflection while it stays as good. The silhouette criterion is
max(Knotwork's, 1 px): the metric counts whole pixels. Last, Knotwork and the peer are
timed alternately (--time-frames, ROUNDS rounds each, median of the rounds) in the same run,
with their peak RSS (/usr/bin/time) and GPU bytes, and one Markdown row per model is printed.

Needs a display for OpenGL: run it under xvfb-run, e.g.

  XDG_RUNTIME_DIR=/tmp/xdg xvfb-run -a -s "-screen 0 1280x1024x24" \\
    python3 tools/peer_search.py --knotwork build/bin/knotwork --work /tmp/peer \\
    tests/data/hammer.iges tests/data/screw.step ...
"""

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import time

# Linear deflection as a fraction of the largest bounding-box side, angular in degrees; the
# joint steps run from OCCT viewers' default (0.004, 20 deg) down by about 1.4x per step in
# angle and 2x in distance (a chord's deflection grows with the square of its angle).
LINEAR = [4e-3 / 2.0 ** k for k in range(16)]
ANGULAR = [round(20.0 / 2.0 ** (k / 2.0), 3) for k in range(16)]
TIME = "/usr/bin/time"


class Failed(Exception):
    pass


def run(cmd, env, fatal=True):
    """Runs cmd; returns (stdout, stderr, seconds). On failure exits with the message, or
    raises Failed when not fatal."""
    start = time.monotonic()
    p = subprocess.run(cmd, env=env, capture_output=True, text=True)
    seconds = time.monotonic() - start
    if p.returncode != 0:
        message = "failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr)
        if fatal:
            sys.exit(message)
        raise Failed(message)
    return p.stdout, p.stderr, seconds


def number(pattern, text, default=None):
    m = re.search(pattern, text)
    return float(m.group(1)) if m else default


class Model:
    def __init__(self, args, cad):
        self.args = args
        self.cad = cad
        self.name = os.path.splitext(os.path.basename(cad))[0]
        self.dir = os.path.join(args.work, self.name + ("_zoom%g" % args.zoom
                                                        if args.zoom != 1.0 else ""))
        self.label = self.name + (" (%g× close-up)" % args.zoom if args.zoom != 1.0 else "")
        os.makedirs(self.dir, exist_ok=True)
        self.knot = os.path.join(self.dir, self.name + ".knot")
        self.env = dict(os.environ, QT_QPA_PLATFORM="xcb")

    def render(self, tag, extra, frames=0):
        """render at the size with --edge-report (frames == 0) or --time-frames; the numbers."""
        out_png = os.path.join(self.dir, tag + ".png")
        cmd = [self.args.knotwork, "render", self.knot, "-o", out_png, "--size",
               "%dx%d" % (self.args.size, self.args.size)] + extra
        if self.args.zoom != 1.0:
            cmd += ["--zoom", repr(self.args.zoom)]
        if os.access(TIME, os.X_OK):  # Debian's package "time"; without it no peak RSS
            cmd = [TIME, "-f", "maxrss_kb %M"] + cmd
        report = os.path.join(self.dir, tag + ".json")
        if frames:
            cmd += ["--time-frames", str(frames)]
        else:
            cmd += ["--edge-report", report]
        out, err, _ = run(cmd, self.env)
        r = {"gpu_bytes": number(r"(\d+) bytes resident on the GPU", out),
             "maxrss_kb": number(r"maxrss_kb (\d+)", err)}
        if frames:
            r["frame_ms"] = number(r"median frame ([\d.]+) ms", out)
        else:
            with open(report) as f:
                r.update(json.load(f))
        r["cells"] = number(r"partitions: (\d+) cells", out)
        r["triangles"] = number(r"peer mesh .*?: (\d+) triangles", out)
        return r

    def mesh(self, lin_frac, ang):
        obj = os.path.join(self.dir, "mesh_%g_%g.obj" % (lin_frac, ang))
        cmd = [self.args.knotwork, "mesh", self.cad, "-o", obj, "--linear-deflection",
               repr(lin_frac * self.side), "--angular-deflection", repr(ang)]
        # Not fatal: a very fine mesh can pass the CAD child's time limit; the search stops there.
        out, _, seconds = run(cmd, self.env, fatal=False)
        return obj, int(number(r"(\d+) triangles", out)), seconds

    def peer_quality(self, li, ai):
        key = (li, ai)
        if key not in self.tried:
            obj, tris, seconds = self.mesh(LINEAR[li], ANGULAR[ai])
            q = self.render("peer_%d_%d" % (li, ai), ["--peer-mesh", obj])
            q.update(obj=obj, triangles=tris, mesh_seconds=seconds, li=li, ai=ai)
            self.tried[key] = q
            print("  %s: linear %.3g (%g x side) angular %g deg: %d triangles, silhouette max "
                  "%.2f px, normal p99 %.4f deg" % (self.name, LINEAR[li] * self.side,
                                                    LINEAR[li], ANGULAR[ai], tris,
                                                    q["silhouetteMaxPixels"],
                                                    q["normalP99Degrees"]), file=sys.stderr)
        return self.tried[key]

    def good(self, q):
        # The silhouette metric scores whole mismatched pixels, so 1 px is its resolution:
        # Knotwork's 0 px on one model and 1 px on another are the same quality.
        # Equal quality is Knotwork's or the bar (normal p99 <= 0.1 deg), whichever is
        # looser: with its per-pixel Newton step Knotwork's p99 is ~0.001 deg, which no mesh
        # with interpolated normals reaches within the triangle cap.
        return (q["normalP99Degrees"] <= max(self.kw["normalP99Degrees"], self.args.normal_p99) and
                q["silhouetteMaxPixels"] <= max(self.kw["silhouetteMaxPixels"], 1.0))

    def search(self):
        run([self.args.knotwork, "convert", self.cad, self.knot], self.env)
        # The largest bounding-box side: the default deflection is 0.004 of it.
        out, _, _ = run([self.args.knotwork, "mesh", self.cad, "-o",
                         os.path.join(self.dir, "default.obj")], self.env)
        self.side = number(r"linear deflection ([\d.e+-]+)", out) / 0.004
        self.kw = self.render("knotwork", [])
        print("  %s: Knotwork silhouette max %.2f px, normal p99 %.4f deg" % (
            self.name, self.kw["silhouetteMaxPixels"], self.kw["normalP99Degrees"]),
            file=sys.stderr)
        self.tried = {}
        self.default = self.peer_quality(0, 0)
        step = 0
        while (not self.good(self.peer_quality(step, step)) and step + 1 < len(LINEAR) and
               self.peer_quality(step, step)["triangles"] < self.args.max_triangles):
            try:
                self.peer_quality(step + 1, step + 1)
            except Failed as e:
                print("  %s: stopped refining: %s" % (self.name, str(e).strip().splitlines()[-1]),
                      file=sys.stderr)
                break
            step += 1
        best = self.peer_quality(step, step)
        # Relax one deflection at a time while the quality holds and triangles drop.
        improved = True
        while improved and self.good(best):
            improved = False
            for li, ai in ((best["li"] - 1, best["ai"]), (best["li"], best["ai"] - 1)):
                if li < 0 or ai < 0:
                    continue
                try:
                    q = self.peer_quality(li, ai)
                except Failed:
                    continue
                if self.good(q) and q["triangles"] < best["triangles"]:
                    best, improved = q, True
        self.best = best
        return best

    def time_both(self):
        kw_ms, peer_ms = [], []
        for _ in range(self.args.rounds):
            kw_ms.append(self.render("knotwork_t", [], self.args.frames)["frame_ms"])
            peer_ms.append(self.render("peer_t", ["--peer-mesh", self.best["obj"]],
                                       self.args.frames)["frame_ms"])
        self.kw_ms = statistics.median(kw_ms)
        self.peer_ms = statistics.median(peer_ms)

    def row(self):
        b, k = self.best, self.kw
        met = "" if self.good(b) else " (not reached)"
        def rss(r):
            return "%.0f MB" % (r["maxrss_kb"] / 1024.0) if r["maxrss_kb"] else "n/a"

        rss_ratio = ("%.2f×" % (k["maxrss_kb"] / b["maxrss_kb"])
                     if k["maxrss_kb"] and b["maxrss_kb"] else "n/a")
        return ("| %s | %.3g / %g°%s | %d | %.2f / %.4f | %.1f (%.1f FPS) | %.1f MB / %s | "
                "%.2f / %.4f | %d cells | %.1f (%.1f FPS) | %.1f MB / %s | %.2f× | %.2f× / "
                "%s | %.1f s |" % (
                    self.label, LINEAR[b["li"]] * self.side, ANGULAR[b["ai"]], met, b["triangles"],
                    b["silhouetteMaxPixels"], b["normalP99Degrees"], self.peer_ms,
                    1000.0 / self.peer_ms, b["gpu_bytes"] / 1e6, rss(b),
                    k["silhouetteMaxPixels"], k["normalP99Degrees"], k["cells"], self.kw_ms,
                    1000.0 / self.kw_ms, k["gpu_bytes"] / 1e6, rss(k),
                    self.peer_ms / self.kw_ms, k["gpu_bytes"] / b["gpu_bytes"], rss_ratio,
                    b["mesh_seconds"]))


HEADER = ("| model | peer deflection linear / angular | peer triangles | peer silhouette max px / "
          "normal p99° | peer frame ms | peer GPU / peak RSS | Knotwork silhouette max px / "
          "normal p99° | Knotwork base polygon | Knotwork frame ms | Knotwork GPU / peak RSS | "
          "FPS Knotwork/peer | GPU / RSS Knotwork/peer | peer meshing |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|---|")


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+", help="IGES, STEP or BREP files")
    ap.add_argument("--knotwork", default="build/bin/knotwork")
    ap.add_argument("--work", default="/tmp/peer_search")
    ap.add_argument("--size", type=int, default=1024)
    ap.add_argument("--frames", type=int, default=15, help="--time-frames per timing run")
    ap.add_argument("--rounds", type=int, default=3, help="alternating timing rounds")
    ap.add_argument("--zoom", type=float, default=1.0,
                    help="render --zoom F: a close-up F times magnified (default 1: fitted)")
    ap.add_argument("--normal-p99", type=float, default=0.1,
                    help="the quality bar when Knotwork's own is finer (default 0.1 deg)")
    ap.add_argument("--max-triangles", type=int, default=4000000,
                    help="stop refining past a mesh of this many triangles")
    args = ap.parse_args()
    rows = []
    for cad in args.files:
        m = Model(args, cad)
        m.search()
        m.time_both()
        d = m.default
        print("  %s: OCCT viewer default (%.3g, 20°): %d triangles, silhouette max %.2f px, "
              "normal p99 %.3f deg" % (m.name, LINEAR[0] * m.side, d["triangles"],
                                       d["silhouetteMaxPixels"], d["normalP99Degrees"]),
              file=sys.stderr)
        rows.append(m.row())
        print(rows[-1], file=sys.stderr)
    print("load average: %.2f %.2f %.2f" % os.getloadavg())
    print(HEADER)
    for r in rows:
        print(r)


if __name__ == "__main__":
    main()
