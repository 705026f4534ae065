#!/usr/bin/env python3
"""geotex inscription: engraved letters (and raised bosses) on a worn stone, with ground truth.

    bench/experiments/inscription.py OUT.ply OUT.truth.json [--case NAME] [--spacing H]
                                     [--seed S] [--noise A] [--noise-seed N]

Engraved letters on an open, gently curved, worn stone surface, as `geotex synth` builds
sphere-1: a mesh and its ground truth, so that the texels found and the words given to the
letters can be scored. The cases (--case; `--list` prints them):

  words    (default) the inscription case of the words experiment (bench/experiments/words.py),
           described below; its output does not change with the options added for the others;
  short    the scale cases of issue 20 (bench/experiments/scale_cases.py): a short inscription
           in large, broad letters, "SPQR" / "ROMA" (cap height 0.22, groove width 0.036), and
           8 raised bosses (16 details), noisy;
  long     a long inscription in small letters, "IMP CAESAR" / "DIVI F AVGVSTVS" / "COS XI"
           (cap height 0.085, groove width 0.01), and 4 bosses (31 details), noisy;
  mixed    both letter sizes on one stone: "SPQR" large above "DIVI F AVGVSTVS" / "COS XI"
           small, and 4 bosses (26 details), noisy: the case where no single scale serves.

  surface  a section of a vertical cylinder of radius 2 (units of the mesh), 1.4 wide (arc
           length) and 0.9 high, triangulated on a regular grid of spacing H (default 0.004:
           157,500 triangles), open (it has a boundary);
  relief   four broad, low swellings and hollows (Gaussian, sigma 0.22 to 0.35, amplitude
           0.006 to 0.012) and erosion: 24 plane waves of wavelength 0.05 to 0.2 (RMS depth
           about 0.0006) and 12 shallow pits (sigma 0.008, depth 0.0012): a worn face, far
           below the letters;
  letters  two lines, "SPQR" (cap height 0.15, groove depth 0.008, width 0.016) and "AVGVSTO"
           (cap height 0.13, depth 0.006, width 0.014), made of straight and curved strokes
           (polylines; arcs cut in 3-degree steps). A groove's cross-section is
           cos^2(pi/2 d/w) of the distance d to the stroke's centre line for d < w, the union
           of a letter's strokes taken as their maximum; its depth is worn by a factor 0.65
           to 1 that varies slowly along the line;
  truth    as `geotex synth`'s: the grey value of a vertex is its groove profile (1 on the
           centre line, 0.5 at d = w/2); a face belongs to a letter when the mean grey of its
           vertices exceeds 0.5, to the letter of its greyest vertex. One shape per letter,
           kind "letter", engraved.

The scale cases add, with the same surface, relief and wear:
  bosses   raised smooth domes, height h cos^2(pi/2 d/R) at the distance d < R from the
           centre (R 0.035 to 0.05, h 0.008 to 0.012), worn as the letters; one shape each, kind
           "boss", not engraved, with the letters' grey rule (grey = the cos^2 profile);
  noise    uniform radial noise in [-A, A] (mesh units; default 0.0003 for the scale cases,
           0 for words) from its own seeded generator (--noise-seed), so the relief and the
           letters do not move with it.

Deterministic (Python's random.Random with a fixed seed). Pure Python: no numpy needed.
"""

import argparse
import json
import math
import os
import random
import struct
import sys

RADIUS = 2.0
WIDTH, HEIGHT = 1.4, 0.9

# Glyphs in a box of height 1 (x right, y up from the baseline); each a list of strokes, a
# stroke a polyline. Arcs: ("arc", cx, cy, rx, ry, from_deg, to_deg).
GLYPHS = {
    "S": [[("arc", 0.3, 0.75, 0.28, 0.25, 25, 270)], [("arc", 0.3, 0.25, 0.3, 0.25, 90, -155)]],
    "P": [[(0, 0), (0, 1)], [(0, 1), (0.25, 1), ("arc", 0.25, 0.75, 0.3, 0.25, 90, -90), (0, 0.5)]],
    "Q": [[("arc", 0.38, 0.5, 0.38, 0.5, 0, 360)], [(0.45, 0.18), (0.8, -0.08)]],
    "R": [[(0, 0), (0, 1)], [(0, 1), (0.25, 1), ("arc", 0.25, 0.75, 0.3, 0.25, 90, -90), (0, 0.5)],
          [(0.22, 0.5), (0.6, 0)]],
    "A": [[(0, 0), (0.34, 1), (0.68, 0)], [(0.15, 0.36), (0.53, 0.36)]],
    "V": [[(0, 1), (0.32, 0), (0.64, 1)]],
    "G": [[("arc", 0.38, 0.5, 0.38, 0.5, 40, 335)], [(0.42, 0.42), (0.74, 0.42), (0.74, 0.2)]],
    "T": [[(0, 1), (0.64, 1)], [(0.32, 1), (0.32, 0)]],
    "O": [[("arc", 0.38, 0.5, 0.38, 0.5, 0, 360)]],
    # The letters of the scale cases' texts.
    "I": [[(0, 0), (0, 1)]],
    "M": [[(0, 0), (0.06, 1), (0.4, 0.12), (0.74, 1), (0.8, 0)]],
    "C": [[("arc", 0.4, 0.5, 0.4, 0.5, 45, 315)]],
    "E": [[(0.55, 1), (0, 1), (0, 0), (0.55, 0)], [(0, 0.5), (0.45, 0.5)]],
    "F": [[(0.55, 1), (0, 1), (0, 0)], [(0, 0.5), (0.45, 0.5)]],
    "D": [[(0, 0), (0, 1), (0.2, 1), ("arc", 0.2, 0.5, 0.4, 0.5, 90, -90), (0, 0)]],
    "X": [[(0, 0), (0.64, 1)], [(0, 1), (0.64, 0)]],
}
# (text, baseline v, cap height, depth, groove width w)
LINES = [("SPQR", 0.09, 0.15, 0.008, 0.016), ("AVGVSTO", -0.24, 0.13, 0.006, 0.014)]
LETTER_GAP = 0.55  # space between letters, in cap heights
WORD_GAP = 0.6  # added to the letter gap at a space, in cap heights

# The cases: lines as LINES, bosses as (u, v, radius R, height h) in mesh units, default grid
# spacing and noise amplitude. The large letters of "short" and the small ones of "long" are
# the two sizes of issue 20: a disc narrower than a broad groove breaks a large letter into
# pieces, one wider than the gap between small letters merges them, and those two limits do
# not overlap (bench/RESULTS.md, scale selection). The bosses sit in the margins, clear of the
# grooves, so that no face is claimed by two details.
# "words" is the inscription of the words experiment, unchanged.
CASES = {
    "words": {"lines": LINES, "bosses": [], "spacing": 0.004, "noise": 0.0},
    "short": {"lines": [("SPQR", 0.07, 0.22, 0.012, 0.036), ("ROMA", -0.27, 0.22, 0.012, 0.036)],
              "bosses": [(u, v, 0.05, 0.012) for u in (-0.6, 0.6) for v in (-0.37, 0.37)]
              + [(u, v, 0.035, 0.008) for u in (-0.61, 0.61) for v in (-0.12, 0.12)],
              "spacing": 0.004, "noise": 0.0003},
    "long": {"lines": [("IMP CAESAR", 0.15, 0.085, 0.005, 0.01), ("DIVI F AVGVSTVS", -0.04, 0.085, 0.005, 0.01),
                       ("COS XI", -0.23, 0.085, 0.005, 0.01)],
             "bosses": [(u, v, 0.04, 0.01) for u in (-0.6, 0.6) for v in (-0.34, 0.34)],
             "spacing": 0.003, "noise": 0.0003},
    "mixed": {"lines": [("SPQR", 0.1, 0.22, 0.012, 0.036), ("DIVI F AVGVSTVS", -0.1, 0.085, 0.005, 0.01),
                        ("COS XI", -0.29, 0.085, 0.005, 0.01)],
              "bosses": [(u, v, 0.04, 0.01) for u in (-0.6, 0.6) for v in (-0.34, 0.34)],
              "spacing": 0.003, "noise": 0.0003},
}


def glyph_width(ch):
    xs = []
    for stroke in GLYPHS[ch]:
        for p in expand(stroke):
            xs.append(p[0])
    return max(xs) - min(xs), min(xs)


def expand(stroke):
    """A stroke as a list of points (arcs cut into 3-degree steps)."""
    pts = []
    for item in stroke:
        if item[0] == "arc":
            _, cx, cy, rx, ry, a0, a1 = item
            n = max(2, int(abs(a1 - a0) / 3) + 1)
            for k in range(n + 1):
                a = math.radians(a0 + (a1 - a0) * k / n)
                pts.append((cx + rx * math.cos(a), cy + ry * math.sin(a)))
        else:
            pts.append(item)
    return pts


def seg_distance(px, py, ax, ay, bx, by):
    dx, dy = bx - ax, by - ay
    L2 = dx * dx + dy * dy
    t = 0.0 if L2 == 0 else max(0.0, min(1.0, ((px - ax) * dx + (py - ay) * dy) / L2))
    ex, ey = ax + t * dx - px, ay + t * dy - py
    return math.sqrt(ex * ex + ey * ey)


def layout(lines):
    """Letters as (glyph, line index, segments in (u, v), bounding box, depth, width)."""
    letters = []
    for li, (text, base, cap, depth, w) in enumerate(lines):
        glyphs = text.replace(" ", "")
        widths = [glyph_width(ch) for ch in glyphs]
        # The space term is last so that a text without spaces (words) sums as it always did.
        total = sum(wd for wd, _ in widths) * cap + LETTER_GAP * cap * (len(glyphs) - 1) + WORD_GAP * cap * text.count(" ")
        x = -total / 2
        spaces_before = [text[:k].count(" ") for k in range(len(text)) if text[k] != " "]
        for n, (ch, (wd, x0)) in enumerate(zip(glyphs, widths)):
            if n > 0 and spaces_before[n] > spaces_before[n - 1]:
                x += WORD_GAP * cap * (spaces_before[n] - spaces_before[n - 1])
            segs = []
            for stroke in GLYPHS[ch]:
                pts = [(x + (p[0] - x0) * cap, base + p[1] * cap) for p in expand(stroke)]
                segs += [(a[0], a[1], b[0], b[1]) for a, b in zip(pts, pts[1:])]
            us = [s[0] for s in segs] + [s[2] for s in segs]
            vs = [s[1] for s in segs] + [s[3] for s in segs]
            box = (min(us) - w, max(us) + w, min(vs) - w, max(vs) + w)
            letters.append({"glyph": ch, "line": li, "segments": segs, "box": box, "depth": depth, "width": w})
            x += wd * cap + LETTER_GAP * cap
    return letters


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh", nargs="?")
    ap.add_argument("truth", nargs="?")
    ap.add_argument("--case", default="words", choices=sorted(CASES), help="which inscription (default: words)")
    ap.add_argument("--list", action="store_true", help="print the cases, their details and faces, and exit")
    ap.add_argument("--spacing", type=float, help="grid spacing (mesh units; default: the case's, 0.004 or 0.003)")
    ap.add_argument("--seed", type=int, default=2019, help="seed of the relief and the wear")
    ap.add_argument("--noise", type=float, help="radial noise amplitude A, uniform in [-A, A] (mesh units; default: "
                    "the case's, 0.0003, or 0 for words)")
    ap.add_argument("--noise-seed", dest="noise_seed", type=int, default=1, help="seed of the noise (default 1)")
    args = ap.parse_args()
    case = CASES[args.case]
    if args.list:
        for name, c in sorted(CASES.items()):
            n = sum(len(t.replace(" ", "")) for t, *_ in c["lines"]) + len(c["bosses"])
            nu, nv = int(round(WIDTH / c["spacing"])), int(round(HEIGHT / c["spacing"]))
            print("%-6s %2d details  %7d faces  %s" % (name, n, 2 * nu * nv, " / ".join(t for t, *_ in c["lines"])))
        return 0
    if not args.mesh or not args.truth:
        ap.error("the mesh and truth paths are required")
    if args.spacing is None:
        args.spacing = case["spacing"]
    if args.noise is None:
        args.noise = case["noise"]
    if not 0.001 <= args.spacing <= 0.02:
        sys.exit("inscription: --spacing must be in [0.001, 0.02]")
    if not 0 <= args.noise <= 0.01:
        sys.exit("inscription: --noise must be in [0, 0.01]")
    lines, bosses = case["lines"], case["bosses"]
    rng = random.Random(args.seed)
    nu, nv = int(round(WIDTH / args.spacing)), int(round(HEIGHT / args.spacing))
    us = [-WIDTH / 2 + WIDTH * i / nu for i in range(nu + 1)]
    vs = [-HEIGHT / 2 + HEIGHT * j / nv for j in range(nv + 1)]

    swell = [(rng.uniform(-0.6, 0.6), rng.uniform(-0.35, 0.35), rng.uniform(0.22, 0.35),
              rng.choice((-1, 1)) * rng.uniform(0.006, 0.012)) for _ in range(4)]
    waves = []
    for _ in range(24):
        lam, ang = rng.uniform(0.05, 0.2), rng.uniform(0, math.pi)
        k = 2 * math.pi / lam
        waves.append((k * math.cos(ang), k * math.sin(ang), rng.uniform(0, 2 * math.pi), 0.00018 * rng.uniform(0.5, 1.5)))
    pits = [(rng.uniform(-0.65, 0.65), rng.uniform(-0.4, 0.4)) for _ in range(12)]
    wear = [(rng.uniform(2, 6), rng.uniform(0, 2 * math.pi)) for _ in range(3)]

    def relief(u, v):
        d = 0.0
        for cu, cv, s, a in swell:
            d += a * math.exp(-((u - cu) ** 2 + (v - cv) ** 2) / (2 * s * s))
        for ku, kv, ph, a in waves:
            d += a * math.sin(ku * u + kv * v + ph)
        for pu, pv in pits:
            r2 = (u - pu) ** 2 + (v - pv) ** 2
            if r2 < 0.0025:
                d -= 0.0012 * math.exp(-r2 / (2 * 0.008 ** 2))
        return d

    def wear_factor(u):
        # Slowly varying in [0.65, 1]: some letters worn more than others.
        s = sum(math.sin(f * u + ph) for f, ph in wear) / 3.0
        return 0.825 + 0.175 * s

    letters = layout(lines)
    nvert = (nu + 1) * (nv + 1)
    grey = [0.0] * nvert
    owner = [-1] * nvert
    groove = [0.0] * nvert
    for li, L in enumerate(letters):
        u0, u1, v0, v1 = L["box"]
        i0, i1 = max(0, int((u0 + WIDTH / 2) / WIDTH * nu)), min(nu, int((u1 + WIDTH / 2) / WIDTH * nu) + 1)
        j0, j1 = max(0, int((v0 + HEIGHT / 2) / HEIGHT * nv)), min(nv, int((v1 + HEIGHT / 2) / HEIGHT * nv) + 1)
        w = L["width"]
        for j in range(j0, j1 + 1):
            for i in range(i0, i1 + 1):
                u, v = us[i], vs[j]
                d = min(seg_distance(u, v, *s) for s in L["segments"])
                if d >= w:
                    continue
                g = math.cos(0.5 * math.pi * d / w) ** 2
                k = j * (nu + 1) + i
                if g > grey[k]:
                    grey[k], owner[k] = g, li
                    groove[k] = L["depth"] * g * wear_factor(u)
    raised = [0.0] * nvert if bosses else None
    for bi, (bu, bv, R, h) in enumerate(bosses):
        i0, i1 = max(0, int((bu - R + WIDTH / 2) / WIDTH * nu)), min(nu, int((bu + R + WIDTH / 2) / WIDTH * nu) + 1)
        j0, j1 = max(0, int((bv - R + HEIGHT / 2) / HEIGHT * nv)), min(nv, int((bv + R + HEIGHT / 2) / HEIGHT * nv) + 1)
        for j in range(j0, j1 + 1):
            for i in range(i0, i1 + 1):
                u, v = us[i], vs[j]
                d = math.hypot(u - bu, v - bv)
                if d >= R:
                    continue
                k = j * (nu + 1) + i
                if owner[k] >= 0:
                    # A case table error: the truth rule gives each face one detail.
                    sys.exit("inscription: case %s: boss %d touches detail %d" % (args.case, bi, owner[k]))
                g = math.cos(0.5 * math.pi * d / R) ** 2
                grey[k], owner[k] = g, len(letters) + bi
                raised[k] = h * g * wear_factor(u)
    # Its own generator: the noise changes no other draw, so a case with and without noise
    # has the same relief, letters and truth.
    noise_rng = random.Random(args.noise_seed) if args.noise > 0 else None
    positions = []
    for j in range(nv + 1):
        for i in range(nu + 1):
            u, v = us[i], vs[j]
            r = RADIUS + relief(u, v) - groove[j * (nu + 1) + i]
            if raised is not None:
                r += raised[j * (nu + 1) + i]
            if noise_rng is not None:
                r += noise_rng.uniform(-args.noise, args.noise)
            a = u / RADIUS
            positions.append((r * math.sin(a), v, r * math.cos(a) - RADIUS))
    faces = []
    for j in range(nv):
        for i in range(nu):
            a, b = j * (nu + 1) + i, j * (nu + 1) + i + 1
            c, d = a + nu + 1, b + nu + 1
            # Alternate the diagonal so that the grid has no preferred direction.
            if (i + j) % 2 == 0:
                faces += [(a, b, d), (a, d, c)]
            else:
                faces += [(a, b, c), (b, d, c)]
    face_shape = []
    for f in faces:
        if (grey[f[0]] + grey[f[1]] + grey[f[2]]) / 3.0 <= 0.5:
            face_shape.append(-1)
            continue
        best = max(f, key=lambda k: grey[k])
        face_shape.append(owner[best])

    # The words case's header and truth are kept byte for byte (words.py's input); the others
    # name their case and say what they add.
    what = " / ".join(t for t, *_ in lines)
    if args.case != "words":
        what = "case %s, %s, %d bosses, noise %g (seed %d)" % (args.case, what, len(bosses), args.noise, args.noise_seed)
    with open(args.mesh, "wb") as out:
        out.write(("ply\nformat binary_little_endian 1.0\ncomment geotex inscription: %s, spacing %g, seed %d\n"
                   "element vertex %d\nproperty double x\nproperty double y\nproperty double z\n"
                   "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (
                       what, args.spacing, args.seed, len(positions), len(faces))).encode())
        out.write(b"".join(struct.pack("<3d", *p) for p in positions))
        out.write(b"".join(struct.pack("<B3i", 3, *f) for f in faces))
    shapes = []
    for li, L in enumerate(letters):
        u0, u1, v0, v1 = L["box"]
        cu, cv = (u0 + u1) / 2, (v0 + v1) / 2
        shapes.append({"id": li, "kind": "letter", "family": "letter", "engraved": True, "glyph": L["glyph"],
                       "line": L["line"], "center": [RADIUS * math.sin(cu / RADIUS), cv, RADIUS * math.cos(cu / RADIUS) - RADIUS],
                       "half_length": (max(u1 - u0, v1 - v0) - 2 * L["width"]) / 2, "half_width": L["width"] / 2,
                       "depth": L["depth"], "groove_width": L["width"]})
    for bi, (bu, bv, R, h) in enumerate(bosses):
        # half_length: the radius where the grey is 0.5, the edge of the boss in the truth.
        shapes.append({"id": len(letters) + bi, "kind": "boss", "family": "boss", "engraved": False,
                       "center": [RADIUS * math.sin(bu / RADIUS), bv, RADIUS * math.cos(bu / RADIUS) - RADIUS],
                       "half_length": R / 2, "half_width": R / 2, "height": h, "radius": R})
    truth = {"geotex": {"document": "ground_truth", "schema": 1, "generator": "bench/experiments/inscription.py"},
             "mesh": {"file": os.path.basename(args.mesh), "vertices": len(positions), "faces": len(faces)},
             "parameters": {"radius": RADIUS, "width": WIDTH, "height": HEIGHT, "spacing": args.spacing, "seed": args.seed,
                            "lines": [{"text": t, "baseline": b, "cap_height": c, "depth": dp, "groove_width": w}
                                      for t, b, c, dp, w in lines], "wear": [0.65, 1.0]},
             "shapes": shapes, "face_shape": face_shape}
    if args.case != "words":
        truth["parameters"].update({"case": args.case, "bosses": [{"center_uv": [bu, bv], "radius": R, "height": h}
                                                                  for bu, bv, R, h in bosses],
                                    "noise": args.noise, "noise_seed": args.noise_seed})
    with open(args.truth, "w") as f:
        json.dump(truth, f)
        f.write("\n")
    covered = sum(1 for s in face_shape if s >= 0)
    print("inscription: %d faces (%d in %d letters%s); wrote %s and %s" % (
        len(faces), covered, len(letters), " and %d bosses" % len(bosses) if bosses else "", args.mesh, args.truth))
    return 0


if __name__ == "__main__":
    sys.exit(main())
