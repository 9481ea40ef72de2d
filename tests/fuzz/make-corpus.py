#!/usr/bin/python3
"""Writes the seed corpus of the fuzz targets (tests/fuzz/corpus/<target>/) into OUTDIR, deterministically.

Usage: /usr/bin/python3 tests/fuzz/make-corpus.py tests/fuzz/corpus
The byte layouts are those decoded by vpFuzzInput.h and the fuzz_<target>.cpp sources: small, valid-looking
inputs that reach deep code paths (real objects, morphs, servo loops) plus a few boundary cases; the fuzzers
mutate from there. A ctest checks that the committed seed-* files are exactly what this script writes (other
files of the corpus are inputs merged from fuzzing runs by `./vispmorph fuzz --update-corpus`).
"""
import json
import math
import os
import struct
import sys


def write(outdir, target, name, data):
    d = os.path.join(outdir, target)
    os.makedirs(d, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(d, "seed-" + name), "wb") as f:
        f.write(bytes(data))


def int8(v):
    v = int(round(v))
    assert -128 <= v <= 127
    return v & 0xFF


def coords(points):
    """Coordinates as vpFuzzInput::coordinate() small integers (tag 2, then an int8)."""
    out = []
    for x, y in points:
        out += [2, int8(x), 2, int8(y)]
    return out


def regular(n, r, phase=0.0, cx=0.0, cy=0.0):
    return [(cx + r * math.cos(phase + 2 * math.pi * k / n), cy + r * math.sin(phase + 2 * math.pi * k / n))
            for k in range(n)]


def star(n, r1, r2):
    return [((r1 if k % 2 == 0 else r2) * math.cos(math.pi * k / n), (r1 if k % 2 == 0 else r2) * math.sin(math.pi * k / n))
            for k in range(2 * n)]


L_SHAPE = [(0, 0), (40, 0), (40, 10), (10, 10), (10, 50), (0, 50)]
KEY = [(0, 0), (60, 0), (60, 6), (54, 6), (54, 12), (48, 12), (48, 6), (30, 6), (30, 20), (0, 20)]


def contour_extraction(out):
    t = "contour_extraction"

    def image(name, w, h, mode, pix):
        write(out, t, name, [w, h, mode] + pix)

    def grey(w, h, f):
        return [f(u, v) for v in range(h) for u in range(w)]

    image("square-dark-on-light", 16, 16, 0, grey(16, 16, lambda u, v: 40 if 4 <= u < 12 and 5 <= v < 11 else 200))
    image("disc-light-on-dark", 20, 20, 0, grey(20, 20, lambda u, v: 220 if (u - 9.5) ** 2 + (v - 9) ** 2 < 40 else 30))
    image("touching-border", 12, 10, 0, grey(12, 10, lambda u, v: 10 if u < 5 else 240))
    image("two-objects", 24, 12, 0, grey(24, 12, lambda u, v: 0 if (2 <= u < 8 or 12 <= u < 22) and 3 <= v < 9 else 255))
    image("ring-with-hole", 16, 16, 0,
          grey(16, 16, lambda u, v: 0 if 9 < (u - 7.5) ** 2 + (v - 7.5) ** 2 < 36 else 255))
    image("checkerboard", 8, 8, 0, grey(8, 8, lambda u, v: 255 * ((u + v) % 2)))
    image("gradient", 16, 16, 0, grey(16, 16, lambda u, v: (u * 16 + v) % 256))
    image("uniform", 8, 8, 0, [77])
    image("too-small", 2, 2, 0, [0, 255, 255, 0])
    image("l-shape-blocks4", 14, 14, 6,
          grey(14, 14, lambda u, v: 20 if (2 <= u < 5 and 2 <= v < 12) or (2 <= u < 11 and 9 <= v < 12) else 230))
    rgb = []
    for v in range(12):
        for u in range(12):
            rgb += [200, 30, 30] if 3 <= u < 9 and 3 <= v < 9 else [30, 200, 30]
    image("colour-square", 12, 12, 1, rgb)
    image("thin-line", 10, 10, 0, grey(10, 10, lambda u, v: 0 if u == 4 else 255))


def polygon_correspondence(out):
    t = "polygon_correspondence"

    # A closed 8-connected walk around a 6x6 square (direction d: du = d % 3 - 1, dv = d // 3 % 3 - 1).
    walk = [5] * 6 + [7] * 6 + [3] * 6 + [1] * 6
    square_chain = [len(walk) - 1, 1] + walk

    def pair(name, A, B, flags=0, scale=0, chain=None):
        data = [flags, scale, len(A) - 1, len(B) - 1] + coords(A) + coords(B)
        write(out, t, name, data + (square_chain if chain is None else chain))

    pair("square-triangle", regular(4, 30), regular(3, 30))
    pair("square-rotated", regular(4, 30), regular(4, 30, 0.7), flags=0x10)
    pair("star-pentagon", star(5, 40, 15), regular(5, 35), flags=0x40)
    pair("l-key", L_SHAPE, KEY, flags=0x80)
    pair("reversed-orientation", regular(6, 25), list(reversed(regular(6, 25, 0.3))), flags=0x28)
    pair("no-scale-normalisation", regular(8, 50), regular(7, 10), flags=0x02)
    pair("elongation", [(0, 0), (60, 0), (60, 10), (0, 10)], [(0, 0), (10, 0), (10, 60), (0, 60)], flags=0x40)
    pair("scaled-tiny", regular(5, 100), regular(5, 100, 1.0), scale=7)  # 1e-9
    pair("scaled-huge", regular(5, 100), regular(5, 100, 1.0), scale=11)  # 1e300
    # Hard values: a NaN vertex, an infinite one, duplicates.
    nan_a = [0, 0, 3, 2, 0, 2, 0, 2, 30, 2, 0, 1, 0, 2, 20, 2, 30, 2, 0]
    write(out, t, "nan-vertex", nan_a + [2, 0, 2, 0, 2, 9, 2, 0, 2, 0, 2, 9] + [9, 1] + [2, 4, 7, 6, 2, 1, 5, 3, 0, 8])
    write(out, t, "inf-vertex", [0, 0, 2, 2] + [2, 0, 2, 0, 1, 1, 2, 0, 2, 10, 2, 10] + [2, 0, 2, 0, 2, 5, 2, 0, 2, 0, 2, 5])
    write(out, t, "duplicates", [0, 0, 3, 2] + coords([(0, 0), (0, 0), (10, 0), (10, 10)]) + coords(regular(3, 10)))
    write(out, t, "raw-doubles", [0, 0, 2, 2] + sum(([0] + list(struct.pack("<d", v)) for v in
                                                     (0.0, 0.0, 1e-200, 0.0, 0.0, 1e-200, 5e-324, 5e-324,
                                                      1.0, 1.0, 1e100, 2.0)), []) + coords(regular(3, 10)))
    # Chains for the polygonal approximation: a closed 8-connected square walk, and arbitrary points.
    diag = [8] * 5 + [6] * 5 + [3] * 10  # a right triangle with a diagonal edge
    pair("chain-triangle-walk", regular(3, 10), regular(3, 10), chain=[len(diag) - 1, 1] + diag)
    pts = coords([(0, 0), (5, 0), (9, 3), (9, 8), (4, 9), (0, 5), (0, 0), (3, 3)])
    pair("chain-arbitrary-points", regular(3, 10), regular(3, 10), chain=[7, 0] + pts)


def database_json(out):
    t = "database_json"

    def db(model, templates, points=48, scales=(0.01, 0.05, 0.1), mirrors=True, calibrated=False, support=None):
        within = [0.1] * len(templates) if calibrated else []
        between = ([None] if len(templates) == 1 else [0.5] * len(templates)) if calibrated else []
        calibration = {"calibrated": calibrated, "manual": False, "threshold": None, "slack": 1.25,
                       "within": within, "between": between}
        if support is not None:  # absent: the files written before the support existed
            calibration["support"] = support
        return {
            "format": "vispmorph-template-database", "version": 1,
            "distance": {"model": model, "points": points, "mirrors": mirrors, "scales": list(scales),
                         "ks": 1.0, "kb": 0.2, "cs": 0.5},
            "calibration": calibration,
            "templates": templates,
        }

    def tpl(name, pts, units="pixel", region=None, image=""):
        o = {"name": name, "image": image, "units": units,
             "x": [round(p[0], 6) for p in pts], "y": [round(p[1], 6) for p in pts],
             "cdMo": [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0.5, 0, 0, 0, 1], "metadata": {"kind": "seed"}}
        if region:
            o["region"] = region
        return o

    sq = [(100 + p[0], 100 + p[1]) for p in regular(4, 30, math.pi / 4)]
    tri = [(200 + p[0], 150 + p[1]) for p in regular(3, 40)]
    key = [(50 + x, 60 + y) for x, y in KEY]
    write(out, t, "polygon-two", json.dumps(db("polygon", [tpl("square", sq), tpl("triangle", tri)]), indent=1))
    write(out, t, "multiscale-calibrated",
          json.dumps(db("multiscale", [tpl("key", key), tpl("l", L_SHAPE)], calibrated=True, support=0.75), indent=1))
    write(out, t, "paper-one", json.dumps(db("paper", [tpl("star", [(p[0] + 80, p[1] + 80) for p in star(5, 40, 15)])],
                                             points=64, scales=(0.0,), calibrated=True)))
    write(out, t, "region-normalized",
          json.dumps(db("polygon", [tpl("sq", [(p[0] / 800.0, p[1] / 800.0) for p in regular(4, 30)], "normalized",
                                        {"area": 0.0028, "cx": 0.0, "cy": 0.0, "mu20": 0.0002, "mu11": 0.0,
                                         "mu02": 0.0002})])))
    write(out, t, "empty-templates", json.dumps(db("multiscale", [])))
    write(out, t, "wrong-version", json.dumps({"format": "vispmorph-template-database", "version": 2}))
    text = json.dumps(db("polygon", [tpl("square", sq)]))
    write(out, t, "truncated", text[: len(text) // 2])
    write(out, t, "not-an-object", "[1, 2, 3]")


def servo(out):
    t = "servo"

    def loop(name, target, moves, flags=0, depth=0, gain=127, nsub=4, scale=0):
        data = [flags, depth, gain, nsub, scale, len(target) - 3] + coords(target) + [len(moves) - 1]
        for m in moves:
            data += m
        write(out, t, name, data)

    def sim(theta_deg, tx, ty, s=1.0, jitter=None):
        m = [2, int(round(theta_deg / 360.0 * 256)) % 256, int8(tx / 2), int8(ty / 2), int(round((s - 0.5) * 128))]
        return m + (jitter or [])

    key = [(x - 30, y - 10) for x, y in KEY]
    loop("key-rotated", key, [sim(150, 20, -10), sim(148, 18, -9), sim(140, 16, -8), sim(130, 14, -7)])
    loop("l-translated-stock", L_SHAPE, [sim(0, 40, 30), sim(0, 38, 29), sim(0, 36, 27)], flags=1)
    loop("square-scaled-about-centroid", regular(4, 40), [sim(30, 0, 0, 1.3), sim(28, 0, 0, 1.28)], flags=2, nsub=0)
    loop("pentagon-lost-then-found", regular(5, 40), [[0], sim(10, 4, 4), [0], sim(9, 4, 4)], flags=4)
    loop("hexagon-jitter", regular(6, 50), [sim(90, 10, 10, 1.0, [1, 255, 2, 254, 0, 3, 253, 1, 0, 0, 5, 251])] * 3,
         flags=8)
    loop("arbitrary-current", regular(4, 40), [[1, 1] + coords(regular(4, 20, 0.3)), [1, 0] + coords(star(5, 30, 10))],
         depth=2)
    loop("same-as-target", regular(8, 60), [sim(0, 0, 0), sim(0, 0, 0)], nsub=0)
    loop("tiny-depth", regular(4, 40), [sim(45, 10, 0)], depth=4)


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make-corpus.py OUTDIR")
    out = sys.argv[1]
    contour_extraction(out)
    polygon_correspondence(out)
    database_json(out)
    servo(out)


if __name__ == "__main__":
    main()
