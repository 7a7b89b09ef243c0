#!/usr/bin/env python3
"""Lower bounds on an adaptive frame's time (docs/PERFORMANCE.md
## Edges, "How fast an adaptive frame can be").

Any renderer that meets the exact renderer's other requirements must at least (1) rasterise the adaptive
base polygon (item 2: within 0.5 px of the surface on screen) once and (2) evaluate and shade
every covered pixel once. This times, interleaved in one run (ROUNDS rounds, median of each
variant's medians of `knotwork render --time-frames`):

  U   uniform 10 x 10, the paper's method (the frame-time target's reference);
  U0  the same with the exact pass's shader returning a constant (the geometry, pre-pass and
      trim passes of uniform 10 x 10 alone);
  A   adaptive, the default;
  G   the adaptive polygon drawn once (`--depth exact-depth`, no pre-pass) with the exact
      pass's shader returning a constant and no skirts or fins: what item 2's polygon costs
      before a single pixel is evaluated;
  P   the OpenCASCADE mesh peer (`--peer FILE=LINEAR,ANGULAR`: `knotwork mesh` at those
      deflections, drawn with `render --peer-mesh`), where given;
  AN  with --newton-too: adaptive with `--no-analytic` (analytic faces by the Newton step).

--cpu reads each run's process CPU per frame (`process CPU N ms`, llvmpipe's threads
included) instead of its wall median: on a machine shared with other jobs the wall time
measures the load as much as the frame.

floor = G + (U - U0): the adaptive polygon once, plus per-pixel evaluation, shading and trims no
dearer than uniform 10 x 10's, whose large cells pass their control points as flat inputs (the
cheapest evaluation the renderer has). It leaves out what the other targets need on top: the
Newton step onto the pixel's ray (normal error p99 <= 0.1 deg; without it the teapot's is 0.3
deg), the skirts and fins (0 crack pixels), and any cost of shading small cells. A frame-time
target below floor / U, or a peer target above P / floor, cannot be met on the machine measured
by an implementation that rasterises today's adaptive polygon and evaluates its pixels no more
cheaply than uniform 10 x 10 does.

U0 and G read a copy of shaders/ (KW_SHADER_DIR) with an early return at the top of
exact_surface.frag's main() in the exact pass's variants (not the pre-pass's G-buffer variant,
the skirts' or the trim pre-pass's).

Needs a display for OpenGL: run it under xvfb-run, e.g.

  XDG_RUNTIME_DIR=/tmp/xdg xvfb-run -a -s "-screen 0 1280x1024x24" python3 tools/speed_floor.py \\
    resources/samples/sphere.knot tests/data/screw.step --peer tests/data/screw.step=0.0665,5
"""

import argparse
import os
import shutil
import statistics
import sys

sys.dont_write_bytecode = True  # no tools/__pycache__ in the source tree from ctest
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from peer_search import number, run  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ANCHOR = "void main() {\n"
NO_OP = ("#if !defined(KW_GBUFFER) && !defined(KW_SKIRT) && !defined(KW_DEPTH_ONLY)\n"
         "    fragColor = vec4(0.5, 0.5, 0.5, 1.0); // tools/speed_floor.py: no evaluation\n"
         "    return;\n"
         "#endif\n")


def no_op_shaders(work):
    """A copy of shaders/ whose exact pass returns a constant colour; its folder."""
    folder = os.path.join(work, "shaders_no_op")
    shutil.rmtree(folder, ignore_errors=True)
    shutil.copytree(os.path.join(ROOT, "shaders"), folder)
    path = os.path.join(folder, "exact_surface.frag")
    with open(path) as f:
        text = f.read()
    if text.count(ANCHOR) != 1:
        sys.exit("speed_floor.py: %s has no single '%s' to patch" % (path, ANCHOR.strip()))
    with open(path, "w") as f:
        f.write(text.replace(ANCHOR, ANCHOR + NO_OP))
    return folder


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+", help=".knot projects or files `knotwork convert` reads")
    ap.add_argument("--peer", action="append", default=[], metavar="FILE=LINEAR,ANGULAR",
                    help="also time the OCCT mesh of FILE at these deflections (absolute, deg)")
    ap.add_argument("--knotwork", default=os.path.join(ROOT, "build/bin/knotwork"))
    ap.add_argument("--work", default="/tmp/speed_floor")
    ap.add_argument("--size", type=int, default=1024)
    ap.add_argument("--zoom", type=float, default=1.0)
    ap.add_argument("--frames", type=int, default=15, help="--time-frames per run")
    ap.add_argument("--rounds", type=int, default=3, help="interleaved rounds")
    ap.add_argument("--newton-too", action="store_true",
                    help="also time adaptive with --no-analytic (AN)")
    ap.add_argument("--cpu", action="store_true",
                    help="process CPU per frame instead of the wall median")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    env = dict(os.environ, QT_QPA_PLATFORM="xcb")
    env.pop("KW_SHADER_DIR", None)
    peers = {}
    for spec in args.peer:
        path, _, defl = spec.rpartition("=")
        linear, _, angular = defl.partition(",")
        if not path or not linear or not angular:
            sys.exit("speed_floor.py: --peer takes FILE=LINEAR,ANGULAR, not '%s'" % spec)
        peers[os.path.abspath(path)] = (linear, angular)
    unknown = set(peers) - {os.path.abspath(f) for f in args.files}
    if unknown:
        sys.exit("speed_floor.py: --peer names a file that is not timed: %s" %
                 ", ".join(sorted(unknown)))
    no_op = no_op_shaders(args.work)

    variants = [("U", {}, ["--partition-mode", "uniform", "--partitions", "10"]),
                ("U0", {"KW_SHADER_DIR": no_op}, ["--partition-mode", "uniform", "--partitions",
                                                  "10"]),
                ("A", {}, []),
                ("G", {"KW_SHADER_DIR": no_op, "KW_EDGE_SKIRTS": "0", "KW_FINS": "0"},
                 ["--depth", "exact-depth"])]
    if args.newton_too:
        variants.append(("AN", {}, ["--no-analytic"]))
    print("| model | view | U: uniform 10 × 10 | U0: its geometry and trims | A: adaptive | "
          "G: adaptive polygon once | floor = G + U − U0 | A / U | floor / U | P: peer | "
          "FPS Knotwork/peer now (P / A) | at best (P / floor) |" +
          (" AN: --no-analytic | P / AN |" if args.newton_too else ""))
    print("|---|---|---|---|---|---|---|---|---|---|---|---|" +
          ("---|---|" if args.newton_too else ""))
    for path in args.files:
        label = os.path.basename(path)  # teapot.knot and teapot.igs are different models
        name = label.replace(".", "_")
        model = os.path.abspath(path)
        if not model.endswith(".knot"):
            knot = os.path.join(args.work, name + ".knot")
            run([args.knotwork, "convert", model, knot], env)
        else:
            knot = model
        mine = list(variants)
        if model in peers:
            obj = os.path.join(args.work, name + ".obj")
            linear, angular = peers[model]
            run([args.knotwork, "mesh", model, "-o", obj, "--linear-deflection", linear,
                 "--angular-deflection", angular], env)
            mine.append(("P", {}, ["--peer-mesh", obj]))
        times = {tag: [] for tag, _, _ in mine}
        for r in range(args.rounds):
            for tag, extra_env, extra in (mine if r % 2 == 0 else mine[::-1]):
                cmd = [args.knotwork, "render", knot, "-o",
                       os.path.join(args.work, "%s_%s.png" % (name, tag)), "--size",
                       "%dx%d" % (args.size, args.size), "--time-frames", str(args.frames)]
                if args.zoom != 1.0:
                    cmd += ["--zoom", repr(args.zoom)]
                out, err, _ = run(cmd + extra, dict(env, **extra_env))
                t = number(r"process CPU ([\d.]+) ms" if args.cpu else r"median frame ([\d.]+) ms",
                           out + err)
                if t is None:
                    sys.exit("speed_floor.py: %s printed no median frame time: %s" %
                             (cmd[0], " ".join(cmd[1:] + extra)))
                times[tag].append(t)
        ms = {tag: statistics.median(v) for tag, v in times.items()}
        floor = ms["G"] + ms["U"] - ms["U0"]
        peer = ms.get("P")
        times_ms = ["%.2f" % v for v in (ms["U"], ms["U0"], ms["A"], ms["G"], floor)]
        row = ([label, "fitted" if args.zoom == 1.0 else "%g×" % args.zoom] + times_ms +
               ["%.2f×" % (ms["A"] / ms["U"]), "**%.2f×**" % (floor / ms["U"]),
                "%.2f" % peer if peer else "—",
                "%.2f×" % (peer / ms["A"]) if peer else "—",
                "**%.2f×**" % (peer / floor) if peer else "—"])
        if args.newton_too:
            row += ["%.2f" % ms["AN"], "%.2f×" % (peer / ms["AN"]) if peer else "—"]
        print("| " + " | ".join(row) + " |", flush=True)


if __name__ == "__main__":
    main()
