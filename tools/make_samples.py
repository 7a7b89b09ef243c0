#!/usr/bin/env python3
"""Generates the sample projects in resources/samples/ (.knot format 1.0, docs/FILE_FORMAT.md).

Re-runnable and deterministic: `python3 tools/make_samples.py` rewrites every sample from the
constructions below and from tests/data/teapot.igs (IGES 5.x, entity 128). Standard library only.
`--check` writes nothing and exits 1 if a committed sample differs from what the script makes
(the test samples_up_to_date runs it).
"""

import json
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SAMPLES = os.path.join(ROOT, "resources", "samples")
TEAPOT_IGES = os.path.join(ROOT, "tests", "data", "teapot.igs")

CHECK_ONLY = "--check" in sys.argv[1:]  # compare with the files instead of writing them
STALE = []

S2 = math.sqrt(0.5)  # weight of the middle point of a 90-degree rational quadratic arc


# ---------------------------------------------------------------- writing .knot JSON


def num(x):
    """Shortest exact decimal of a double (Python's repr), ints as ints."""
    if isinstance(x, int):
        return str(x)
    if not math.isfinite(x):
        raise ValueError("non-finite number %r" % x)
    return repr(float(x))


def numbers(xs):
    return "[" + ", ".join(num(x) for x in xs) + "]"


def points_block(points, indent):
    pad = " " * indent
    return "[\n" + ",\n".join(pad + "  " + numbers(p) for p in points) + "\n" + pad + "]"


def curve_json(c, indent):
    pad = " " * indent
    return ("{\n%s  \"degree\": %d,\n%s  \"knots\": %s,\n%s  \"points\": %s,\n"
            "%s  \"weights\": %s\n%s}") % (pad, c["degree"], pad, numbers(c["knots"]), pad,
                                           points_block(c["points"], indent + 2), pad,
                                           numbers(c["weights"]), pad)


def surface_json(s):
    pad = "    "
    lines = [pad + "{"]
    lines.append('%s  "id": %d,' % (pad, s["id"]))
    lines.append('%s  "name": %s,' % (pad, json.dumps(s["name"])))
    for key in ("degreeU", "degreeV", "countU", "countV"):
        lines.append('%s  "%s": %d,' % (pad, key, s[key]))
    lines.append('%s  "knotsU": %s,' % (pad, numbers(s["knotsU"])))
    lines.append('%s  "knotsV": %s,' % (pad, numbers(s["knotsV"])))
    lines.append('%s  "points": %s,' % (pad, points_block(s["points"], len(pad) + 2)))
    lines.append('%s  "weights": %s,' % (pad, numbers(s["weights"])))
    loops = []
    for loop in s.get("trims", []):
        curves = ",\n".join(pad + "        " + curve_json(c, len(pad) + 8) for c in loop["curves"])
        loops.append('%s    {\n%s      "id": %d,\n%s      "curves": [\n%s\n%s      ]\n%s    }'
                     % (pad, pad, loop["id"], pad, curves, pad, pad))
    lines.append('%s  "trims": [%s%s],' % (pad, "\n" + ",\n".join(loops) + "\n" + pad + "  "
                                           if loops else "", ""))
    lines.append('%s  "partitions": %s,' % (pad, numbers(s["partitions"])))
    m = s["material"]
    lines.append('%s  "material": {"color": %s, "ka": %s, "kd": %s, "ks": %s, "shininess": %s}%s'
                 % (pad, numbers(m["color"]), num(m["ka"]), num(m["kd"]), num(m["ks"]),
                    num(m["shininess"]), "," if "solid" in s else ""))
    if "solid" in s:  # format 1.2: a face of a closed solid (docs/FILE_FORMAT.md, "Solid")
        lines.append('%s  "solid": {"index": %d, "outside": %s}'
                     % (pad, s["solid"][0], json.dumps(s["solid"][1])))
    lines.append(pad + "}")
    return "\n".join(lines)


def default_lights():
    def unit(v):
        n = math.sqrt(sum(c * c for c in v))
        return [c / n for c in v]
    return [
        {"kind": "directional", "vector": unit([-0.4, -0.6, 0.7]),
         "ambient": [0.2, 0.2, 0.2], "diffuse": [0.8, 0.8, 0.8], "specular": [0.6, 0.6, 0.6]},
        {"kind": "directional", "vector": unit([0.7, -0.3, 0.2]),
         "ambient": [0.0, 0.0, 0.0], "diffuse": [0.35, 0.35, 0.35],
         "specular": [0.15, 0.15, 0.15]},
    ]


def write_knot(name, surfaces, lights=None):
    ids = [s["id"] for s in surfaces] + [l["id"] for s in surfaces for l in s.get("trims", [])]
    assert len(ids) == len(set(ids)), "duplicate ids in " + name
    light_text = ",\n".join(
        '    {"kind": %s, "vector": %s, "ambient": %s, "diffuse": %s, "specular": %s}'
        % (json.dumps(l["kind"]), numbers(l["vector"]), numbers(l["ambient"]),
           numbers(l["diffuse"]), numbers(l["specular"])) for l in (lights or default_lights()))
    # 1.0 unless a surface uses a member of a later minor version.
    version = "1.2" if any("solid" in s for s in surfaces) else "1.0"
    text = ('{\n  "format": "knotwork",\n  "version": "%s",\n  "nextId": %d,\n'
            '  "surfaces": [\n%s\n  ],\n  "lights": [\n%s\n  ]\n}\n'
            % (version, max(ids) + 1, ",\n".join(surface_json(s) for s in surfaces),
               light_text))
    json.loads(text)  # the output must be valid JSON
    path = os.path.join(SAMPLES, name)
    if CHECK_ONLY:
        try:
            with open(path, encoding="utf-8") as f:
                same = f.read() == text
        except OSError:
            same = False
        if not same:
            STALE.append(os.path.relpath(path, ROOT))
        return
    with open(path, "w", encoding="utf-8", newline="\n") as f:
        f.write(text)
    print("wrote %s (%d surfaces)" % (os.path.relpath(path, ROOT), len(surfaces)))


def material(color, ka=0.15, kd=0.75, ks=0.35, shininess=40.0):
    return {"color": color, "ka": ka, "kd": kd, "ks": ks, "shininess": shininess}


def surface(sid, name, du, dv, ku, kv, points, weights=None, trims=None, partitions=(10, 10),
            mat=None):
    cu = len(ku) - du - 1
    cv = len(kv) - dv - 1
    assert len(points) == cu * cv, name
    return {"id": sid, "name": name, "degreeU": du, "degreeV": dv, "countU": cu, "countV": cv,
            "knotsU": ku, "knotsV": kv, "points": points,
            "weights": weights if weights is not None else [1.0] * len(points),
            "trims": trims or [], "partitions": list(partitions),
            "material": mat or material([0.8, 0.82, 0.86])}


# ---------------------------------------------------------------- bicubic.knot


def bicubic():
    # 6 x 5 control points; u knots non-uniform with a double interior knot at 0.35.
    ku = [0.0, 0.0, 0.0, 0.0, 0.35, 0.35, 1.0, 1.0, 1.0, 1.0]
    kv = [0.0, 0.0, 0.0, 0.0, 0.3, 1.0, 1.0, 1.0, 1.0]
    cu, cv = len(ku) - 4, len(kv) - 4
    pts = []
    for j in range(cv):          # index(i, j) = j * countU + i
        for i in range(cu):
            x = -2.0 + 4.0 * i / (cu - 1)
            y = -1.5 + 3.0 * j / (cv - 1)
            z = round(0.6 * math.sin(1.7 * x) * math.cos(1.3 * y), 6)
            pts.append([x, y, z])
    s = surface(1, "Wavy bicubic patch", 3, 3, ku, kv, pts,
                mat=material([0.85, 0.55, 0.25], ks=0.5, shininess=60.0))
    write_knot("bicubic.knot", [s])


# ---------------------------------------------------------------- sphere.knot, torus.knot

# The standard 9-point circle (The NURBS Book, 7.5): a square's corners and edge midpoints,
# degree 2, double interior knots at the quarters, corner weights sqrt(2)/2.
CIRCLE_XY = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0)]
CIRCLE_W = [1.0, S2, 1.0, S2, 1.0, S2, 1.0, S2, 1.0]
CIRCLE_KNOTS = [0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0]
# Half circle from the south pole to the north pole in the (r, z) half plane.
HALF_RZ = [(0, -1), (1, -1), (1, 0), (1, 1), (0, 1)]
HALF_W = [1.0, S2, 1.0, S2, 1.0]
HALF_KNOTS = [0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0]


def revolve(profile, profile_w):
    """Surface of revolution about z (NURBS Book A8.1 with the 9-point circle): u around the
    axis, v along the profile given as (r, z) points."""
    pts, ws = [], []
    for (r, z), wv in zip(profile, profile_w):
        for (cx, cy), wu in zip(CIRCLE_XY, CIRCLE_W):
            pts.append([float(r * cx), float(r * cy), float(z)])
            ws.append(wu * wv)
    return pts, ws


def sphere():
    pts, ws = revolve(HALF_RZ, HALF_W)
    s = surface(1, "Unit sphere", 2, 2, CIRCLE_KNOTS, HALF_KNOTS, pts, ws, partitions=(16, 8),
                mat=material([0.3, 0.55, 0.85], ks=0.6, shininess=80.0))
    # Closed (the seam at u = 0 = 1, the poles collapsed), S_u x S_v pointing out: the renderer
    # may skip its polygon's back faces (docs/RENDERING.md, "Back faces of closed solids").
    s["solid"] = (0, "normal")
    write_knot("sphere.knot", [s])


def torus(major=2.0, minor=0.6):
    profile = [(major + minor * x, minor * y) for x, y in CIRCLE_XY]
    pts, ws = revolve(profile, CIRCLE_W)
    s = surface(1, "Torus R2 r0.6", 2, 2, CIRCLE_KNOTS, CIRCLE_KNOTS, pts, ws,
                partitions=(24, 12), mat=material([0.8, 0.35, 0.35], ks=0.45, shininess=50.0))
    s["solid"] = (0, "normal")  # closed in u and v, S_u x S_v pointing out, as the sphere's
    write_knot("torus.knot", [s])


# ---------------------------------------------------------------- trimmed_plate.knot


def line(a, b):
    return {"degree": 1, "knots": [0.0, 0.0, 1.0, 1.0], "points": [list(a), list(b)],
            "weights": [1.0, 1.0]}


def quarter_arc(centre, radius, start_deg):
    """Counter-clockwise 90-degree rational quadratic arc; the middle point is the corner of
    the tangent lines, with weight cos(45 deg)."""
    a0, a1 = math.radians(start_deg), math.radians(start_deg + 90)
    cx, cy = centre
    p0 = [cx + radius * round(math.cos(a0)), cy + radius * round(math.sin(a0))]
    p2 = [cx + radius * round(math.cos(a1)), cy + radius * round(math.sin(a1))]
    p1 = [p0[0] + p2[0] - cx, p0[1] + p2[1] - cy]
    return {"degree": 2, "knots": [0.0, 0.0, 0.0, 1.0, 1.0, 1.0], "points": [p0, p1, p2],
            "weights": [1.0, S2, 1.0]}


def polyline(points):
    n = len(points)
    ks = [0.0] + [k / (n - 1) for k in range(n)] + [1.0]
    return {"degree": 1, "knots": ks, "points": [list(p) for p in points], "weights": [1.0] * n}


def trimmed_plate():
    # A gently curved biquadratic plate over [0, 1]^2.
    ku = kv = [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]
    n = len(ku) - 3
    pts = []
    for j in range(n):
        for i in range(n):
            x, y = -2.0 + 4.0 * i / (n - 1), -1.5 + 3.0 * j / (n - 1)
            pts.append([x, y, 0.08 * (x * x - 0.5 * y * y)])
    # Outer loop: a rounded rectangle in (u, v), corners of radius 0.1.
    lo, hi, r = 0.04, 0.96, 0.1
    outer = [line((lo + r, lo), (hi - r, lo)), quarter_arc((hi - r, lo + r), r, -90),
             line((hi, lo + r), (hi, hi - r)), quarter_arc((hi - r, hi - r), r, 0),
             line((hi - r, hi), (lo + r, hi)), quarter_arc((lo + r, hi - r), r, 90),
             line((lo, hi - r), (lo, lo + r)), quarter_arc((lo + r, lo + r), r, 180)]
    # Hole 1: a circle of four rational quarter arcs.
    circle = [quarter_arc((0.3, 0.62), 0.14, a) for a in (0, 90, 180, 270)]
    # Hole 2: a concave five-pointed star, one closed degree-1 curve.
    star = []
    for k in range(11):
        a = math.radians(90 + 36 * (k % 10))
        rad = 0.17 if k % 2 == 0 else 0.07
        star.append((round(0.68 + rad * math.cos(a), 12), round(0.36 + rad * math.sin(a), 12)))
    star[-1] = star[0]
    trims = [{"id": 2, "curves": outer}, {"id": 3, "curves": circle},
             {"id": 4, "curves": [polyline(star)]}]
    s = surface(1, "Trimmed plate", 2, 2, ku, kv, pts, trims=trims, partitions=(12, 12),
                mat=material([0.45, 0.7, 0.45], ks=0.3, shininess=30.0))
    write_knot("trimmed_plate.knot", [s])


# ---------------------------------------------------------------- star_island.knot


def star_points(cx, cy, r_out, r_in, tips, turn_deg=90.0, clockwise=False):
    pts = []
    for k in range(2 * tips + 1):
        a = math.radians(turn_deg + (-1 if clockwise else 1) * 180.0 / tips * (k % (2 * tips)))
        rad = r_out if k % 2 == 0 else r_in
        pts.append((round(cx + rad * math.cos(a), 12), round(cy + rad * math.sin(a), 12)))
    pts[-1] = pts[0]
    return pts


def star_island():
    # A slightly domed bicubic plate over [0, 1]^2, trimmed by loops of mixed orientation:
    # the domain boundary itself (clockwise), a concave six-pointed star hole (counter-
    # clockwise), and a circular hole (clockwise arcs) holding a concave star island.
    ku = kv = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0]
    n = len(ku) - 4
    pts = []
    for j in range(n):
        for i in range(n):
            x, y = -2.0 + 4.0 * i / (n - 1), -1.5 + 3.0 * j / (n - 1)
            pts.append([x, y, 0.15 - 0.05 * (x * x + y * y)])
    boundary = [polyline([(0.0, 0.0), (0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)])]
    star_hole = [polyline(star_points(0.27, 0.5, 0.2, 0.08, 6))]
    circle = [trim_curve_reversed(quarter_arc((0.7, 0.5), 0.24, a)) for a in (270, 180, 90, 0)]
    island = [polyline(star_points(0.7, 0.5, 0.17, 0.07, 5, clockwise=True))]
    trims = [{"id": 2, "curves": boundary}, {"id": 3, "curves": star_hole},
             {"id": 4, "curves": circle}, {"id": 5, "curves": island}]
    s = surface(1, "Star and island", 3, 3, ku, kv, pts, trims=trims, partitions=(10, 10),
                mat=material([0.85, 0.6, 0.3], ks=0.3, shininess=30.0))
    write_knot("star_island.knot", [s])


def trim_curve_reversed(c):
    """The same curve run backwards over the same (0..1) knot range."""
    ks = c["knots"]
    return {"degree": c["degree"], "knots": [ks[0] + ks[-1] - k for k in reversed(ks)],
            "points": list(reversed(c["points"])), "weights": list(reversed(c["weights"]))}


# ---------------------------------------------------------------- teapot.knot from IGES


def iges_sections(path):
    """Lines of each IGES section keyed by the letter in column 73 (fixed 80-column form)."""
    sections = {}
    with open(path, encoding="ascii", errors="replace") as f:
        for raw in f:
            line = raw.rstrip("\r\n").ljust(80)
            sections.setdefault(line[72], []).append(line)
    return sections


def iges_entities(path):
    """(entity type, parameter tokens) of every directory entry. Pointers from the directory
    entry (field 2: first P line) locate the parameter record, which runs to the record
    delimiter; this file's P-line back-pointers (columns 65-72) and D sequence numbers are not
    reliable, so they are not used."""
    sec = iges_sections(path)
    glob = "".join(l[:72] for l in sec.get("G", []))
    pdelim, rdelim = ",", ";"
    if glob.startswith("1H"):
        pdelim = glob[2]
    plines = [l[:64] for l in sec["P"]]
    dlines = sec["D"]
    entities = []
    for k in range(0, len(dlines) - 1, 2):
        etype = int(dlines[k][0:8])
        pstart = int(dlines[k][8:16])
        text = ""
        for l in plines[pstart - 1:]:
            text += l
            if rdelim in l:
                break
        record = text.split(rdelim)[0]
        tokens = [t.strip() for t in record.split(pdelim)]
        if int(tokens[0]) != etype:
            raise ValueError("entity %d: P record starts with %s" % (k // 2, tokens[0]))
        entities.append((etype, tokens[1:]))
    return entities


def iges_real(token):
    return float(token.upper().replace("D", "E"))


def iges_bspline_surface(tokens):
    """IGES entity 128: K1, K2, M1, M2, PROP1..5, knots S, knots T, weights W, points X Y Z,
    then U0, U1, V0, V1 (IGES 5.3, 4.24). Control point (i, j) is stored with i fastest."""
    k1, k2, m1, m2 = (int(t) for t in tokens[0:4])
    it = 9
    def take(n):
        nonlocal it
        vals = [iges_real(t) for t in tokens[it:it + n]]
        if len(vals) != n:
            raise ValueError("entity 128 record is truncated")
        it += n
        return vals
    cu, cv = k1 + 1, k2 + 1
    ku = take(cu + m1 + 1)
    kv = take(cv + m2 + 1)
    w = take(cu * cv)
    xyz = take(3 * cu * cv)
    u0, u1, v0, v1 = take(4)
    if (u0, u1) != (ku[m1], ku[-m1 - 1]) or (v0, v1) != (kv[m2], kv[-m2 - 1]):
        raise ValueError("sub-domain surfaces are not supported")
    pts = [xyz[3 * k:3 * k + 3] for k in range(cu * cv)]
    return m1, m2, ku, kv, pts, w


TEAPOT_PARTS = [  # name, colour: the six classic groups of Newell's teapot
    ("rim", [0.86, 0.78, 0.36]), ("body", [0.8, 0.82, 0.86]), ("lid", [0.36, 0.62, 0.86]),
    ("handle", [0.78, 0.42, 0.3]), ("spout", [0.44, 0.74, 0.46]), ("bottom", [0.62, 0.5, 0.78]),
]


def teapot_part(pts):
    """The group of a patch from its control-point bounds (body radius 2, rim radius 1.5 at
    z 2.4..2.53, lid above z 2.4 inside radius 1.3, handle at x < -1.5, spout at x > 1.7)."""
    xs = [p[0] for p in pts]
    zs = [p[2] for p in pts]
    rmax = max(math.hypot(p[0], p[1]) for p in pts)
    if max(xs) <= -1.5:
        return "handle"
    if min(xs) >= 1.7:
        return "spout"
    if max(zs) <= 0.15:
        return "bottom"
    if min(zs) >= 2.4:
        return "rim" if rmax > 1.6 else "lid"
    return "body"


def teapot():
    surfaces = []
    counts = {}
    for etype, tokens in iges_entities(TEAPOT_IGES):
        if etype != 128:
            continue
        du, dv, ku, kv, pts, w = iges_bspline_surface(tokens)
        part = teapot_part(pts)
        counts[part] = counts.get(part, 0) + 1
        colour = dict(TEAPOT_PARTS)[part]
        surfaces.append(surface(len(surfaces) + 1, "%s %d" % (part, counts[part]), du, dv, ku, kv,
                                pts, w, partitions=(30, 30),
                                mat=material(colour, ks=0.45, shininess=50.0)))
    expected = {"rim": 4, "body": 8, "lid": 8, "handle": 4, "spout": 4, "bottom": 4}
    if counts != expected:
        raise ValueError("unexpected teapot patch groups %r" % counts)
    if len(surfaces) != 32:
        raise ValueError("expected 32 teapot patches, found %d" % len(surfaces))
    if not CHECK_ONLY:
        print("teapot groups:", counts)
    write_knot("teapot.knot", surfaces)


def main():
    os.makedirs(SAMPLES, exist_ok=True)
    bicubic()
    sphere()
    torus()
    trimmed_plate()
    star_island()
    teapot()
    if CHECK_ONLY:
        for path in STALE:
            print("%s differs from what tools/make_samples.py generates; rerun it" % path)
        return 1 if STALE else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
