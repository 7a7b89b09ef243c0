#!/usr/bin/env python3
"""Writes tests/data/broken/*.knot: one defect per file, and EXPECTED.tsv with the JSON path and
a substring of the reason that Knotwork's reader must report for each (tst_knotfile checks them).
Re-runnable; standard library only."""

import copy
import json
import math
import os

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(ROOT, "tests", "data", "broken")
S2 = math.sqrt(0.5)


def base():
    """A small valid scene: one biquadratic 4 x 4 plate with one closed trim loop, two lights."""
    pts = [[float(i), float(j), 0.1 * i * j] for j in range(4) for i in range(4)]
    square = [[0.2, 0.2], [0.8, 0.2], [0.8, 0.8], [0.2, 0.8], [0.2, 0.2]]
    return {
        "format": "knotwork", "version": "1.0", "nextId": 3,
        "surfaces": [{
            "id": 1, "name": "plate", "degreeU": 2, "degreeV": 2, "countU": 4, "countV": 4,
            "knotsU": [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
            "knotsV": [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
            "points": pts, "weights": [1.0] * 16,
            "trims": [{"id": 2, "curves": [{
                "degree": 1, "knots": [0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0],
                "points": square, "weights": [1.0] * 5}]}],
            "partitions": [10, 10],
            "material": {"color": [0.8, 0.5, 0.3], "ka": 0.15, "kd": 0.75, "ks": 0.35,
                         "shininess": 40.0}}],
        "lights": [{"kind": "directional", "vector": [0.0, 0.0, 1.0], "ambient": [0.2] * 3,
                    "diffuse": [0.8] * 3, "specular": [0.6] * 3}],
    }


CASES = []  # (file name, text, JSON path, reason substring)


def case(name, path, reason, edit=None, text=None):
    if text is None:
        scene = base()
        edit(scene)
        text = json.dumps(scene, indent=2) + "\n"
    CASES.append((name, text, path, reason))


def surf(scene):
    return scene["surfaces"][0]


def main():
    valid = json.dumps(base(), indent=2) + "\n"
    case("truncated.knot", "$", "not valid JSON", text=valid[: len(valid) // 2])
    case("not_json.knot", "$", "not valid JSON", text="This is not a Knotwork project.\n")
    case("top_level_array.knot", "$", "expected an object at the top level", text="[1, 2, 3]\n")
    case("empty.knot", "$", "not valid JSON", text="")
    case("wrong_format.knot", "$.format", 'expected "knotwork"',
         lambda s: s.update(format="blender"))
    case("future_version.knot", "$.version", "newer than this Knotwork can read",
         lambda s: s.update(version="2.0"))
    case("missing_surfaces.knot", "$.surfaces", "missing required member",
         lambda s: s.pop("surfaces"))
    case("missing_weights.knot", "$.surfaces[0].weights", "missing required member",
         lambda s: surf(s).pop("weights"))
    case("degree_16.knot", "$.surfaces[0].degreeU", "outside the allowed range [1, 15]",
         lambda s: surf(s).update(degreeU=16))
    case("degree_as_string.knot", "$.surfaces[0].degreeV", 'found the string "2"',
         lambda s: surf(s).update(degreeV="2"))
    case("decreasing_knot.knot", "$.surfaces[0].knotsU[4]", "smaller than the previous knot",
         lambda s: surf(s).update(knotsU=[0.0, 0.0, 0.0, 0.5, 0.25, 1.0, 1.0]))
    case("knot_count.knot", "$.surfaces[0].knotsV", "expected 7 knots",
         lambda s: surf(s).update(knotsV=[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]))
    case("knot_multiplicity.knot", "$.surfaces[0].knotsU[3]", "repeats 4 times",
         lambda s: surf(s).update(knotsU=[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0]))
    case("empty_domain.knot", "$.surfaces[0].knotsU", "is empty",
         lambda s: surf(s).update(knotsU=[0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0]))
    case("nan_string.knot", "$.surfaces[0].points[3][1]", 'found the string "NaN"',
         lambda s: surf(s)["points"][3].__setitem__(1, "NaN"))
    case("number_1e999.knot", "$", "not valid JSON",
         text=valid.replace('"shininess": 40.0', '"shininess": 1e999'))
    case("absurd_counts.knot", "$.surfaces[0].countV", "more than the limit 4000000",
         lambda s: surf(s).update(countU=3000, countV=3000))
    case("point_count.knot", "$.surfaces[0].points", "expected 16 control points",
         lambda s: surf(s)["points"].pop())
    case("point_size.knot", "$.surfaces[0].points[5]", "expected 3 numbers",
         lambda s: surf(s)["points"][5].pop())
    case("negative_weight.knot", "$.surfaces[0].weights[2]", "weight must be positive",
         lambda s: surf(s)["weights"].__setitem__(2, -1.0))
    case("duplicate_surface_id.knot", "$.surfaces[1].id", "id 1 is already used at $.surfaces[0].id",
         lambda s: s["surfaces"].append(copy.deepcopy(surf(s)) | {"trims": []}))
    case("duplicate_loop_id.knot", "$.surfaces[0].trims[0].id",
         "id 1 is already used at $.surfaces[0].id",
         lambda s: surf(s)["trims"][0].update(id=1))
    case("id_zero.knot", "$.surfaces[0].id", "outside the allowed range",
         lambda s: surf(s).update(id=0))
    case("partitions_out_of_range.knot", "$.surfaces[0].partitions[1]",
         "outside the allowed range [1, 256]", lambda s: surf(s).update(partitions=[10, 1000]))
    case("too_many_lights.knot", "$.lights", "9 lights, more than the limit 8",
         lambda s: s.update(lights=s["lights"] * 9))
    case("light_kind.knot", "$.lights[0].kind", 'expected "directional" or "point"',
         lambda s: s["lights"][0].update(kind="spot"))
    case("open_trim_loop.knot", "$.surfaces[0].trims[0].curves[0]", "a trim loop must be closed",
         lambda s: surf(s)["trims"][0]["curves"][0]["points"].__setitem__(4, [0.2, 0.3]))
    case("trim_curve_too_few_points.knot", "$.surfaces[0].trims[0].curves[0].points",
         "a degree-5 curve needs 6 to",
         lambda s: surf(s)["trims"][0]["curves"][0].update(degree=5))
    case("material_color.knot", "$.surfaces[0].material.color[0]",
         "outside the allowed range [0, 1]",
         lambda s: surf(s)["material"].update(color=[1.5, 0.5, 0.5]))
    case("camera_fov.knot", "$.camera.fovYDegrees", "outside the open range (0, 180)",
         lambda s: s.update(camera={"eye": [0.0, -5.0, 3.0], "target": [0.0, 0.0, 0.0],
                                    "up": [0.0, 0.0, 1.0], "fovYDegrees": 200.0}))
    case("integer_expected.knot", "$.surfaces[0].countU", "expected an integer, found 4.5",
         lambda s: surf(s).update(countU=4.5))
    case("hidden_not_bool.knot", "$.surfaces[0].hidden", "expected true or false, found the string",
         lambda s: surf(s).update(hidden="yes"))

    os.makedirs(OUT, exist_ok=True)
    for old in os.listdir(OUT):
        if old.endswith(".knot"):
            os.remove(os.path.join(OUT, old))
    with open(os.path.join(OUT, "EXPECTED.tsv"), "w", encoding="utf-8", newline="\n") as tsv:
        tsv.write("# file\tJSON path\treason substring (written by tools/make_broken_corpus.py)\n")
        for name, text, path, reason in CASES:
            with open(os.path.join(OUT, name), "w", encoding="utf-8", newline="\n") as f:
                f.write(text)
            tsv.write("%s\t%s\t%s\n" % (name, path, reason))
    print("wrote %d broken files to %s" % (len(CASES), os.path.relpath(OUT, ROOT)))


if __name__ == "__main__":
    main()
