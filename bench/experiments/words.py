#!/usr/bin/env python3
"""The words experiment (issue 15): do the concepts given to one kind of shape hold when
nothing but the sampling, the noise, the units, the placement or the relief changes?

    bench/experiments/words.py [--build BUILD] [--out DIR] [--tiny] [--from-json FILE]
                               [--before FILE]

Every run is `geotex annotate MESH --scale r --json report.json --segmentation seg.ply` with
the default dictionary and options. Conditions (full run): sphere-1 (`geotex synth`) at levels
6, 7 and 8; level 7 simplified to 100k, 50k and 25k faces (geotex_simplify, which moves the
ground truth); noise I = 0.1, 0.2, 0.3 with seeds 1 to 3; layout seeds 2 and 3; level 7 with
its coordinates ×1000 and rotated; half the shapes engraved (`--orientation both`); the
inscription of bench/experiments/inscription.py (`--orientation both --scale 0.06`).

Each texel covers the truth shape that holds most of its faces, each texture takes the kind
of most of its texels; the concepts of a kind are those of the texture holding most of its
texels. Scored: per kind, the concepts and their Jaccard index to the reference (level 7);
contradictions judged from the English labels alone (not from the dictionary's metadata);
the rates of the expected words; per feature and kind, how far the mean texel value moves
from the reference. The full run replaces the part of bench/RESULTS.md between
`<!-- words:begin -->` and `<!-- words:end -->`; --from-json rewrites it from a saved
results.json without running; --before adds a column from an earlier results.json.
--tiny (ctest bench_words_tiny) runs levels 5 and 6 and a few conditions in a temporary
directory, changes no file, and fails (exit 1) when an output does not parse, a kind is not
found, a texture contradicts itself or an engraved shape is given a convex word.
"""

import argparse
import array
import datetime
import json
import math
import os
import re
import shutil
import sys
import tempfile
import time

from bench_common import git_commit, replace_section, run_checked, source_of, synth_command

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BEGIN, END = "<!-- words:begin -->", "<!-- words:end -->"

SPHERE_KINDS = ["big_disc", "small_disc", "square", "rectangle"]

# A condition: name, how its mesh is made, the annotate options. "ref" marks the reference.
FULL = {
    "scale": 0.04,
    "reference": "level 7",
    "conditions": (
        [{"name": "level %d" % lv, "group": "level", "synth": {"level": lv}} for lv in (6, 7, 8)]
        + [{"name": "%dk faces" % (n // 1000), "group": "density", "simplify": n} for n in (100000, 50000, 25000)]
        + [{"name": "noise %s seed %d" % (i, s), "group": "noise", "synth": {"level": 7, "noise": i, "seed": s}}
           for i in (0.1, 0.2, 0.3) for s in (1, 2, 3)]
        + [{"name": "layout %d" % s, "group": "layout", "synth": {"level": 7, "layout": s}} for s in (2, 3)]
        + [{"name": "×1000 units", "group": "units", "transform": "scale"},
           {"name": "rotated", "group": "rotation", "transform": "rotate"},
           {"name": "half engraved", "group": "engraved", "synth": {"level": 7, "engraved": 0.5},
            "orientation": "both"},
           {"name": "inscription", "group": "inscription", "inscription": 0.004, "orientation": "both",
            "scale": 0.06}]),
}
TINY = {
    "scale": 0.04,
    "reference": "level 6",
    "conditions": [
        {"name": "level 5", "group": "level", "synth": {"level": 5}},
        {"name": "level 6", "group": "level", "synth": {"level": 6}},
        {"name": "noise 0.1 seed 1", "group": "noise", "synth": {"level": 6, "noise": 0.1, "seed": 1}},
        {"name": "half engraved", "group": "engraved", "synth": {"level": 6, "engraved": 0.5}, "orientation": "both"},
        {"name": "inscription", "group": "inscription", "inscription": 0.008, "orientation": "both", "scale": 0.06},
    ],
}
# The conditions that keep every shape the same (issue item 3: levels, density, rotation,
# units); the feature spread is measured over them, and separately over the noisy ones.
SAME_SHAPE_GROUPS = ("level", "density", "units", "rotation")

# ---- the words, judged from the English labels alone ---------------------------------------
FLAT_WORDS = ("flat", "level", "low curvedness")
CURVED_WORDS = ("curved", "convex", "concave", "dome", "cap", "cup", "ridge", "rut", "trough", "saddle")
CONVEX_WORDS = ("convex", "dome", "cap", "ridge")
CONCAVE_WORDS = ("concave", "cup", "trough", "rut", "groove")
REGULARITY = r"\b(very|strongly|uniform|regular|irregular|varying|variable|constant)\b"


def has_word(label, words):
    label = label.lower()
    return any(re.search(r"\b%s\b" % re.escape(w), label) for w in words)


def is_saddle(label):
    # "saddle ridge", "saddle rut": a saddle is convex one way and concave the other, so it
    # is neither a convex nor a concave word (it is still a curved one).
    return "saddle" in label.lower()


def convex_word(label):
    return not is_saddle(label) and has_word(label, CONVEX_WORDS)


def concave_word(label):
    return not is_saddle(label) and has_word(label, CONCAVE_WORDS)


def label_facet(label):
    """The experiment's own facet of a label (the property it names), or None for the words
    judged by the flat/curved and convex/concave rules instead. Two different labels of one
    facet on one texture contradict each other (a texture has one outline, one size, ...)."""
    s = label.lower()
    if "circular" in s:
        return "outline"
    if re.search(r"\bax[ie]s\b|elongated", s):
        return "elongation"
    if "compact" in s:
        return "compactness"
    if re.search(r"\b(thin|thick)\b", s):
        return "width"
    if re.search(REGULARITY, s) and re.search(r"\b(uniform|regular|irregular|varying|variable|constant)\b", s):
        return "regularity of " + re.sub(r"\s+", " ", re.sub(REGULARITY, "", s)).strip()
    if re.search(r"\b(area|perimeter|size)\b", s) or re.search(r"\b(small|large|tiny|big|medium)\b.*\bregion\b", s):
        return "size"
    if re.search(r"\b(high|low|deep|shallow)\b region", s):
        return "height"
    if re.search(r"\brelief\b", s):
        return "relief"
    return None


def facet_direction(label, facet):
    """What a label says within its facet, coarsely: two labels of one facet that say the same
    (\"small area\", \"very small region\"; \"one dominant axis\", \"elongated shape\") repeat
    each other; two that differ contradict each other."""
    s = label.lower()
    if facet == "size":
        return "small" if re.search(r"\b(small|tiny)\b", s) else "large" if re.search(r"\b(large|big)\b", s) else s
    if facet == "elongation":
        if re.search(r"\bone\b|elongated", s):
            return "one"
        return "two" if re.search(r"\btwo\b", s) else s
    if facet.startswith("regularity"):
        return "irregular" if re.search(r"\b(irregular|varying|variable)\b", s) else "regular"
    if facet == "height":
        return "low" if re.search(r"\b(low|shallow)\b", s) else "high"
    return s


def curved_degree(label):
    s = label.lower()
    if "curved" not in s:
        return None
    if re.search(r"\b(slightly|gently|weakly)\b", s):
        return "slightly"
    if re.search(r"\b(strongly|very|highly)\b", s):
        return "strongly"
    return None


def contradictions(labels, engraved=None):
    """Pairs of labels of one texture that cannot both hold, with the rule. `engraved`: True
    when the texture holds engraved shapes, False raised ones, None unknown."""
    out = []
    for i, a in enumerate(labels):
        for b in labels[i + 1:]:
            fa, fb = label_facet(a), label_facet(b)
            if fa is not None and fa == fb and facet_direction(a, fa) != facet_direction(b, fb):
                out.append(("two concepts of one facet (%s)" % fa, a, b))
            if (has_word(a, FLAT_WORDS) and has_word(b, CURVED_WORDS)) or (has_word(b, FLAT_WORDS) and has_word(a, CURVED_WORDS)):
                out.append(("flat and curved", a, b))
            if (convex_word(a) and concave_word(b)) or (concave_word(a) and convex_word(b)):
                out.append(("convex and concave", a, b))
            da, db = curved_degree(a), curved_degree(b)
            if da and db and da != db:
                out.append(("two degrees of curvature", a, b))
    for a in labels:
        if engraved is True and convex_word(a):
            out.append(("convex word on an engraved shape", a, ""))
        if engraved is False and concave_word(a):
            out.append(("concave word on a raised shape", a, ""))
    return out


# ---- running ---------------------------------------------------------------------------------
class Runner:
    def __init__(self, args, cfg, out):
        self.args, self.cfg, self.out = args, cfg, out
        self.started = time.time()

    def path(self, name):
        return os.path.join(self.out, name)

    def run(self, cmd):
        return run_checked(cmd)[1]

    def synth(self, name, level, noise=0.0, seed=1, layout=1, engraved=0.0):
        mesh, truth = self.path(name + ".ply"), self.path(name + ".truth.json")
        if not os.path.exists(mesh):
            self.run(synth_command(self.args.geotex, mesh, truth, level, noise, seed, layout, engraved))
        return mesh, truth

    def make_mesh(self, cond, slug):
        """The mesh and ground truth of a condition."""
        ref_level = int(re.search(r"\d+", self.cfg["reference"]).group())
        if "synth" in cond:
            s = cond["synth"]
            return self.synth(slug, s["level"], s.get("noise", 0.0), s.get("seed", 1), s.get("layout", 1),
                              s.get("engraved", 0.0))
        if "simplify" in cond:
            mesh, truth = self.synth("level-%d" % ref_level, ref_level)
            smesh, struth = self.path(slug + ".ply"), self.path(slug + ".truth.json")
            self.run([self.args.simplify, mesh, truth, str(cond["simplify"]), smesh, struth])
            return smesh, struth
        if "transform" in cond:
            mesh, truth = self.synth("level-%d" % ref_level, ref_level)
            tmesh = self.path(slug + ".ply")
            transform_ply(mesh, tmesh, cond["transform"])
            return tmesh, truth  # same faces in the same order: the truth holds
        if "inscription" in cond:
            mesh, truth = self.path(slug + ".ply"), self.path(slug + ".truth.json")
            self.run([sys.executable, os.path.join(HERE, "inscription.py"), mesh, truth, "--spacing",
                      repr(cond["inscription"])])
            return mesh, truth
        raise ValueError(cond)

    def annotate(self, cond, slug, mesh):
        rep, seg, ttl = self.path(slug + ".report.json"), self.path(slug + ".seg.ply"), self.path(slug + ".ttl")
        scale = cond.get("scale", self.cfg["scale"])
        cmd = [self.args.geotex, "annotate", mesh, "-o", ttl, "--scale", repr(scale), "--json", rep,
               "--segmentation", seg, "--orientation", cond.get("orientation", "positive")]
        cmd += self.args.annotate_option or []
        secs = self.run(cmd)
        return rep, seg, secs

    def condition(self, cond):
        slug = re.sub(r"[^a-z0-9]+", "-", cond["name"].lower().replace("×", "x")).strip("-")
        t0 = time.time()
        mesh, truth = self.make_mesh(cond, slug)
        rep, seg, secs = self.annotate(cond, slug, mesh)
        with open(rep) as f:
            report = json.load(f)
        with open(truth) as f:
            gt = json.load(f)
        res = analyse(report, gt, seg)
        res.update({"name": cond["name"], "group": cond["group"], "annotate_seconds": secs,
                    "seconds": time.time() - t0, "faces": gt["mesh"]["faces"],
                    "scale": cond.get("scale", self.cfg["scale"]), "orientation": cond.get("orientation", "positive")})
        if not self.args.keep:
            for p in (rep, seg, self.path(slug + ".ttl")):
                if os.path.exists(p):
                    os.remove(p)
            if not re.match(r"level-\d+$", slug):
                for p in (mesh,):
                    if os.path.exists(p):
                        os.remove(p)
        return res


# ---- PLY (binary little endian or ASCII, as geotex writes it) --------------------------------
def read_ply_header(f):
    header = []
    while True:
        line = f.readline()
        if not line:
            raise SystemExit("words: PLY header without end_header")
        line = line.decode("ascii", "replace").rstrip("\r\n")
        header.append(line)
        if line == "end_header":
            return header


def ply_elements(header):
    """[(name, count, [(type, name) or ('list', count_type, item_type, name)])]"""
    elements = []
    for h in header:
        w = h.split()
        if w[:1] == ["element"]:
            elements.append((w[1], int(w[2]), []))
        elif w[:1] == ["property"]:
            elements[-1][2].append(tuple(w[1:]))
    return elements


def transform_ply(src, dst, how):
    """Copies a geotex PLY with its vertices ×1000 or rotated (an arbitrary rotation: 37° about
    (1, 2, 3)/|.|), written as doubles so that no precision is lost; faces and their
    properties are copied byte for byte, so a ground truth per face still applies."""
    with open(src, "rb") as f:
        header = read_ply_header(f)
        if "format binary_little_endian 1.0" not in header:
            raise SystemExit("words: %s: only binary little-endian PLY is transformed" % src)
        elements = ply_elements(header)
        if elements[0][0] != "vertex" or [p[1] for p in elements[0][2]] != ["x", "y", "z"]:
            raise SystemExit("words: %s: expected a vertex element with x y z only" % src)
        n = elements[0][1]
        code = {"float": "f", "float32": "f", "double": "d", "float64": "d"}[elements[0][2][0][0]]
        xyz = array.array(code)
        xyz.frombytes(f.read(n * 3 * xyz.itemsize))
        rest = f.read()
    if sys.byteorder != "little":
        xyz.byteswap()
    if how == "scale":
        m = [[1000.0, 0, 0], [0, 1000.0, 0], [0, 0, 1000.0]]
    else:
        ax = [1 / math.sqrt(14), 2 / math.sqrt(14), 3 / math.sqrt(14)]
        a = math.radians(37.0)
        c, s, t = math.cos(a), math.sin(a), 1 - math.cos(a)
        x, y, z = ax
        m = [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
             [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
             [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]
    out = array.array("d", bytes(8 * 3 * n))
    for i in range(n):
        p0, p1, p2 = xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]
        out[3 * i] = m[0][0] * p0 + m[0][1] * p1 + m[0][2] * p2
        out[3 * i + 1] = m[1][0] * p0 + m[1][1] * p1 + m[1][2] * p2
        out[3 * i + 2] = m[2][0] * p0 + m[2][1] * p1 + m[2][2] * p2
    if sys.byteorder != "little":
        out.byteswap()
    new_header = []
    for h in header:
        w = h.split()
        if w[:1] == ["property"] and len(w) == 3 and w[2] in ("x", "y", "z"):
            h = "property double " + w[2]
        new_header.append(h)
    new_header.insert(2, "comment words experiment: " + ("coordinates x1000" if how == "scale" else
                                                         "rotated 37 degrees about (1, 2, 3)"))
    with open(dst, "wb") as f:
        f.write(("\n".join(new_header) + "\n").encode("ascii"))
        f.write(out.tobytes())
        f.write(rest)


def read_face_texel(seg):
    """The face property `texel` of a segmentation PLY (binary little endian), or None."""
    with open(seg, "rb") as f:
        header = read_ply_header(f)
        if "format binary_little_endian 1.0" not in header:
            return None
        elements = ply_elements(header)
        sizes = {"char": 1, "uchar": 1, "int8": 1, "uint8": 1, "short": 2, "ushort": 2, "int": 4, "uint": 4,
                 "int32": 4, "float": 4, "double": 8}
        for name, count, props in elements:
            if name == "vertex":
                f.seek(count * sum(sizes[p[0]] for p in props), 1)
            elif name == "face":
                data = f.read()
                # geotex writes triangles: uchar 3 + 3 ints, then the int/uchar attributes.
                off, fmt = 0, "<"
                names = []
                for p in props:
                    if p[0] == "list":
                        fmt += "B3i"
                        names += ["n", "a", "b", "c"]
                    else:
                        fmt += {"int": "i", "uchar": "B"}[p[0]]
                        names.append(p[1])
                import struct
                st = struct.Struct(fmt)
                if "texel" not in names:
                    return None
                k = names.index("texel")
                return [rec[k] for rec in st.iter_unpack(data[:count * st.size])]
    return None


# ---- analysis of one run ---------------------------------------------------------------------
def kind_key(shape):
    kind = shape["kind"]
    if shape.get("engraved") and kind != "letter":
        return kind + " (engraved)"
    return kind


def majority(counts):
    """The key with the largest count; ties to the smallest key (deterministic)."""
    return max(sorted(counts), key=lambda k: counts[k]) if counts else None


def analyse(report, truth, seg_path):
    texels = report["texels"]
    ann = report["annotation"]["textures"]
    face_shape = truth["face_shape"]
    shapes = truth["shapes"]
    if len(face_shape) != report["mesh"]["faces"]:
        raise SystemExit("words: the ground truth has %d faces, the report %d" % (len(face_shape), report["mesh"]["faces"]))
    # Face -> texel from the segmentation PLY (the brief's source), checked against the report.
    face_texel = read_face_texel(seg_path)
    if face_texel is not None:
        members = {}
        for fi, t in enumerate(face_texel):
            if t >= 0:
                members.setdefault(t, []).append(fi)
        for i, t in enumerate(texels):
            if "faces" in t and sorted(t["faces"]) != members.get(i, []):
                raise SystemExit("words: texel %d: its faces differ between the report and the segmentation PLY" % i)
    else:
        members = {i: t["faces"] for i, t in enumerate(texels)}
    texel_texture = [t["texture"] for t in texels]
    texel_shape = []
    for i in range(len(texels)):
        count = {}
        for fi in members.get(i, []):
            s = face_shape[fi]
            if s >= 0:
                count[s] = count.get(s, 0) + 1
        texel_shape.append(majority(count))
    texel_kind = [kind_key(shapes[s]) if s is not None else None for s in texel_shape]
    concepts = {}
    withheld = {}
    for t in ann:
        concepts[t["texture"]] = t["concepts"]
        withheld[t["texture"]] = t.get("withheld", [])
    labels = {k: [c["label"] for c in v] for k, v in concepts.items()}
    textures = sorted(set(texel_texture) | set(labels))
    # Texture -> kind (of most of its texels that cover a shape), and relief.
    texture_kind = {}
    for k in textures:
        count = {}
        for i, t in enumerate(texel_texture):
            if t == k and texel_kind[i] is not None:
                count[texel_kind[i]] = count.get(texel_kind[i], 0) + 1
        texture_kind[k] = majority(count)
    # Per kind: texels, the texture holding most of them, its concepts, the share of the
    # kind's texels in textures carrying each label.
    kinds = {}
    for kind in sorted(set(k for k in texel_kind if k is not None)):
        idx = [i for i, k in enumerate(texel_kind) if k == kind]
        count = {}
        for i in idx:
            count[texel_texture[i]] = count.get(texel_texture[i], 0) + 1
        main = majority(count)
        share = {}
        for i in idx:
            for lab in set(labels.get(texel_texture[i], [])):
                share[lab] = share.get(lab, 0) + 1
        shapes_of_kind = [s for s in shapes if kind_key(s) == kind]
        found = len(set(texel_shape[i] for i in idx))
        kinds[kind] = {
            "texels": len(idx), "shapes": len(shapes_of_kind), "shapes_found": found,
            "texture": main, "texture_share": count[main] / len(idx), "textures": len(count),
            "texture_counts": {str(t): n for t, n in sorted(count.items())},
            "concepts": labels.get(main, []),
            "concept_details": concepts.get(main, []),
            "withheld": [c.get("label", c.get("concept")) if isinstance(c, dict) else c for c in withheld.get(main, [])],
            "label_share": {lab: n / len(idx) for lab, n in sorted(share.items())},
            "feature_mean": feature_means([texels[i] for i in idx]),
        }
    # Contradictions: every texture, judged with the relief of the shapes it holds.
    contra = []
    for k in textures:
        kind = texture_kind[k]
        engraved = None if kind is None else (kind.endswith("(engraved)") or kind == "letter")
        for rule, a, b in contradictions(labels.get(k, []), engraved):
            contra.append({"texture": k, "kind": kind, "rule": rule, "labels": [a, b] if b else [a]})
    # Texels of engraved shapes whose texture carries a convex word (and raised/concave).
    convex_on_engraved = concave_on_raised = engraved_texels = raised_texels = 0
    for i, s in enumerate(texel_shape):
        if s is None:
            continue
        labs = labels.get(texel_texture[i], [])
        if shapes[s].get("engraved"):
            engraved_texels += 1
            convex_on_engraved += any(convex_word(x) for x in labs)
        else:
            raised_texels += 1
            concave_on_raised += any(concave_word(x) for x in labs)
    return {
        "texels": len(texels), "textures": len(textures), "spurious_texels": sum(1 for s in texel_shape if s is None),
        "shapes": len(shapes), "kinds": kinds, "contradictions": contra,
        "engraved_texels": engraved_texels, "convex_on_engraved": convex_on_engraved,
        "raised_texels": raised_texels, "concave_on_raised": concave_on_raised,
        "texture_labels": {str(k): labels.get(k, []) for k in textures},
        "texture_kind": {str(k): texture_kind[k] for k in textures},
        "fields": sorted(set(key for v in concepts.values() for c in v for key in c)),
    }


def feature_means(rows):
    sums, counts = {}, {}
    for t in rows:
        for k, v in t.get("features", {}).items():
            if v is None or not isinstance(v, (int, float)) or not math.isfinite(v):
                continue
            sums[k] = sums.get(k, 0.0) + v
            counts[k] = counts.get(k, 0) + 1
    return {k: sums[k] / counts[k] for k in sums}


# ---- summary over the runs -------------------------------------------------------------------
def jaccard(a, b):
    a, b = set(a), set(b)
    return 1.0 if not a and not b else len(a & b) / len(a | b)


def rate(run, kinds, labels):
    """Share of the texels of these kinds in textures carrying one of these labels, or None."""
    total = hit = 0
    for kind in kinds:
        k = run["kinds"].get(kind)
        if not k:
            continue
        for tex, n in k["texture_counts"].items():
            total += n
            if any(lab in run["texture_labels"].get(tex, []) for lab in labels):
                hit += n
    return hit / total if total else None


def summarise(runs, cfg):
    ref = next((r for r in runs if r["name"] == cfg["reference"]), None)
    if ref is None:
        raise SystemExit("words: no reference run (%s)" % cfg["reference"])
    ref_kinds = [k for k in SPHERE_KINDS if k in ref["kinds"]]
    jac = []
    per_run = []
    for r in runs:
        row = {"name": r["name"], "group": r["group"], "jaccard": {}}
        if r["group"] != "inscription" and r is not ref:
            for kind in ref_kinds:
                j = jaccard(r["kinds"][kind]["concepts"], ref["kinds"][kind]["concepts"]) if kind in r["kinds"] else 0.0
                row["jaccard"][kind] = j
                jac.append(j)
        row["disc_circular"] = rate(r, ["big_disc", "small_disc", "big_disc (engraved)", "small_disc (engraved)"],
                                    ["circular shape"])
        row["rect_one_axis"] = rate(r, ["rectangle", "rectangle (engraved)"], ["one dominant axis"])
        row["rect_non_circular"] = rate(r, ["rectangle", "rectangle (engraved)"], ["non circular shape"])
        row["square_expected"] = rate(r, ["square", "square (engraved)"], ["two dominant axes", "close to circular shape"])
        row["contradictions"] = len(r["contradictions"])
        row["convex_on_engraved"] = r["convex_on_engraved"]
        row["concave_on_raised"] = r["concave_on_raised"]
        per_run.append(row)
    levels = [row for row in per_run if row["group"] == "level"]
    rect = [(r["name"], "one dominant axis" in r["kinds"][k]["concepts"]) for r in runs
            for k in ("rectangle", "rectangle (engraved)") if k in r["kinds"]]
    return {
        "mean_jaccard": sum(jac) / len(jac) if jac else None,
        "jaccard_pairs": len(jac),
        "contradictions": sum(len(r["contradictions"]) for r in runs),
        "disc_circular_levels": {row["name"]: row["disc_circular"] for row in levels},
        "rect_one_axis_all": all(ok for _, ok in rect) and bool(rect),
        "rect_missing": [n for n, ok in rect if not ok],
        "convex_on_engraved": sum(r["convex_on_engraved"] for r in runs),
        "engraved_texels": sum(r["engraved_texels"] for r in runs),
        "ref_concepts": {k: len(v["concepts"]) for k, v in ref["kinds"].items()},
        "per_run": per_run,
    }


def feature_spread(runs, cfg):
    """Per feature and kind: the largest deviation of the per-kind mean from the reference's,
    over the same-shape conditions and over the noisy ones: [relative, where, absolute,
    reference mean]. The relative one is what most features are judged by; near a reference of
    0 (a disc's sphericity) only the absolute one means something."""
    ref = next(r for r in runs if r["name"] == cfg["reference"])
    out = {}
    for kind in SPHERE_KINDS:
        if kind not in ref["kinds"]:
            continue
        m0 = ref["kinds"][kind]["feature_mean"]
        for feat, v0 in m0.items():
            for label, groups in (("same", SAME_SHAPE_GROUPS), ("noise", ("noise",))):
                worst, where, worst_abs = 0.0, None, 0.0
                for r in runs:
                    if r is ref or r["group"] not in groups or kind not in r["kinds"]:
                        continue
                    v = r["kinds"][kind]["feature_mean"].get(feat)
                    if v is None:
                        continue
                    dev = abs(v - v0) / abs(v0) if v0 != 0 else (0.0 if v == 0 else float("inf"))
                    if dev > worst or where is None:
                        worst, where, worst_abs = dev, r["name"], abs(v - v0)
                out.setdefault(feat, {}).setdefault(kind, {})[label] = [worst, where, worst_abs, v0]
    return out


# ---- report ----------------------------------------------------------------------------------
def pct(x):
    return "n/a" if x is None else "%.0f%%" % (100 * x)


def met(ok):
    return "met" if ok else "**not met**"


def make_markdown(results, meta, before=None):
    runs, cfg = results["runs"], results["config"]
    S = summarise(runs, cfg)
    B = summarise(before["results"]["runs"], before["results"]["config"]) if before else None
    L = []
    add = L.append
    add("## Words (issue 15)")
    add("")
    add("Made by `%s` on %s; %d cores (`nproc`), shared; geotex at commit %s (harness at %s); total %.0f s. "
        "Every run: `geotex annotate MESH --scale %s --json report.json --segmentation seg.ply`, default dictionary "
        "and options (the inscription: `--orientation both --scale 0.06`, half engraved: `--orientation both`). "
        "A texel covers the truth shape holding most of its faces, a texture takes the kind of most of its texels, "
        "and the concepts of a kind are those of the texture holding most of its texels. Jaccard: of the sets of "
        "English labels, to the reference (%s) per kind. Contradictions are judged from the English labels alone "
        "(bench/README.md, words experiment): two labels of one facet (outline, elongation, size, width, "
        "compactness, height, regularity of one thing), a flat word with a curved one, a convex word with a "
        "concave one, two degrees of curvature, a convex word on an engraved shape, a concave word on a raised one." % (
            meta["command"], meta["date"], meta["nproc"], meta["geotex_commit"], meta["commit"], meta["seconds"],
            cfg["scale"], cfg["reference"]))
    add("")
    add("### Targets")
    add("")
    disc_ok = all(v is not None and v >= 0.9 for v in S["disc_circular_levels"].values())
    ref_min = min(S["ref_concepts"].get(k, 0) for k in SPHERE_KINDS)
    lines = [
        ("Mean Jaccard to %s ≥ 0.9 over all conditions" % cfg["reference"], S["mean_jaccard"] is not None and S["mean_jaccard"] >= 0.9,
         "%.2f over %d kind × condition pairs" % (S["mean_jaccard"] or 0, S["jaccard_pairs"]),
         (lambda b: "%.2f" % (b["mean_jaccard"] or 0))),
        ("0 contradictions", S["contradictions"] == 0, "%d" % S["contradictions"], (lambda b: "%d" % b["contradictions"])),
        ("\"circular shape\" for ≥ 90% of disc texels at levels 6, 7, 8", disc_ok,
         ", ".join("%s: %s" % (k, pct(v)) for k, v in S["disc_circular_levels"].items()),
         (lambda b: ", ".join("%s: %s" % (k, pct(v)) for k, v in b["disc_circular_levels"].items()))),
        ("Rectangles \"one dominant axis\" in every condition", S["rect_one_axis_all"],
         "missing in %d: %s" % (len(S["rect_missing"]), ", ".join(S["rect_missing"])) if S["rect_missing"] else "in all",
         (lambda b: "missing in %d" % len(b["rect_missing"]) if b["rect_missing"] else "in all")),
        ("Engraved shapes never given a convex word", S["convex_on_engraved"] == 0,
         "%d of %d engraved texels" % (S["convex_on_engraved"], S["engraved_texels"]),
         (lambda b: "%d of %d" % (b["convex_on_engraved"], b["engraved_texels"]))),
        ("Each kind described by ≥ 3 concepts at %s" % cfg["reference"], ref_min >= 3,
         ", ".join("%s %d" % (k, S["ref_concepts"].get(k, 0)) for k in SPHERE_KINDS),
         (lambda b: ", ".join("%s %d" % (k, b["ref_concepts"].get(k, 0)) for k in SPHERE_KINDS))),
    ]
    if B:
        add("| target | | now | before (%s) |" % before["meta"]["geotex_commit"])
        add("|---|---|---|---|")
    else:
        add("| target | | measured |")
        add("|---|---|---|")
    for text, ok, now, bf in lines:
        add("| %s | %s | %s |%s" % (text, met(ok), now, " %s |" % bf(B) if B else ""))
    add("")
    worst = sorted(((j, row["name"], k) for row in S["per_run"] for k, j in row["jaccard"].items()))[:5]
    if worst:
        add("Lowest Jaccard: %s. Contradictions by rule: %s." % (
            ", ".join("%s %s %.2f" % (n, k.replace("_", " "), j) for j, n, k in worst),
            ", ".join("%s %d" % kv for kv in sorted(rule_counts(runs).items(), key=lambda kv: -kv[1])) or "none"))
        add("")
    # ---- per condition
    add("### Per condition")
    add("")
    add("Jaccard per kind to %s; rates: share of the kind's texels in textures carrying the expected label "
        "(discs \"circular shape\"; rectangles \"one dominant axis\", \"non circular shape\"; squares \"two dominant "
        "axes\" or \"close to circular shape\"); contradictions: pairs in all the textures of the run." % cfg["reference"])
    add("")
    add("| condition | faces | texels (covering no shape) | textures | J big disc | J small disc | J square | J rectangle | discs circular | "
        "rect. one axis | rect. non circular | squares | contradictions | convex on engraved | s |")
    add("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r, row in zip(runs, S["per_run"]):
        add("| %s | %s | %d (%d) | %d | %s | %s | %s | %s | %s | %s | %s | %s | %d | %s | %.1f |" % (
            r["name"], "{:,}".format(r["faces"]), r["texels"], r["spurious_texels"], r["textures"],
            *[("%.2f" % row["jaccard"][k]) if k in row["jaccard"] else "–" for k in SPHERE_KINDS],
            pct(row["disc_circular"]), pct(row["rect_one_axis"]), pct(row["rect_non_circular"]),
            pct(row["square_expected"]), row["contradictions"],
            ("%d/%d" % (r["convex_on_engraved"], r["engraved_texels"])) if r["engraved_texels"] else "–",
            r["annotate_seconds"]))
    add("")
    # ---- concepts per kind
    add("### Concepts per kind")
    add("")
    add("The labels of the texture holding most of the kind's texels (its share of them in brackets when below "
        "100%); in the engraved condition the engraved shapes are their own kinds. A label in *italics* is not in "
        "the reference's set.")
    add("")
    all_kinds = []
    for r in runs:
        for k in r["kinds"]:
            if k not in all_kinds:
                all_kinds.append(k)
    order = SPHERE_KINDS + sorted(k for k in all_kinds if k not in SPHERE_KINDS)
    ref = next(r for r in runs if r["name"] == cfg["reference"])
    for kind in [k for k in order if k in all_kinds]:
        add("**%s**" % kind.replace("_", " "))
        add("")
        add("| condition | concepts |")
        add("|---|---|")
        base = kind.replace(" (engraved)", "")
        ref_set = set(ref["kinds"].get(base, {}).get("concepts", []))
        for r in runs:
            k = r["kinds"].get(kind)
            if not k:
                continue
            labs = ", ".join(lab if lab in ref_set or not ref_set else "*%s*" % lab for lab in k["concepts"]) or "(none)"
            extra = "" if k["texture_share"] >= 0.999 else " [%s of its texels]" % pct(k["texture_share"])
            wh = "; withheld: %s" % ", ".join(k["withheld"]) if k.get("withheld") else ""
            add("| %s | %s%s%s |" % (r["name"], labs, extra, wh))
        add("")
    # ---- contradictions
    add("### Contradictions")
    add("")
    seen = {}
    for r in runs:
        for c in r["contradictions"]:
            key = (c["rule"], " + ".join(sorted(c["labels"])))
            seen.setdefault(key, []).append("%s (%s)" % (r["name"], (c["kind"] or "no shape").replace("_", " ")))
    if not seen:
        add("None.")
    else:
        add("| rule | labels | where (condition, kind of the texture) |")
        add("|---|---|---|")
        for (rule, labs), where in sorted(seen.items(), key=lambda kv: -len(kv[1])):
            add("| %s | %s | %d: %s |" % (rule, labs, len(where), ", ".join(where[:6]) + (", …" if len(where) > 6 else "")))
    add("")
    # ---- feature spread
    spread = feature_spread(runs, cfg)
    add("### Spread of the texel features")
    add("")
    add("Per feature and kind: the kind's mean texel value at %s (m_ref), then the largest deviation of the "
        "kind's mean from it, absolute |m − m_ref| and relative (|m − m_ref| / |m_ref|, meaningless where m_ref is "
        "near 0, as a disc's sphericity), over the conditions that keep every shape the same (levels, density, "
        "×1000, rotated), and in brackets over the noisy ones. The values come from report.json's per-texel "
        "features; docs/features.md states a tolerance per feature." % cfg["reference"])
    add("")
    add("| feature | %s |" % " | ".join(k.replace("_", " ") for k in SPHERE_KINDS))
    add("|---|%s" % ("---|" * len(SPHERE_KINDS)))
    for feat, per_kind in spread.items():
        cells = []
        for kind in SPHERE_KINDS:
            d = per_kind.get(kind)
            if not d:
                cells.append("–")
                continue
            same, noise = d.get("same", [None, None]), d.get("noise", [None, None])
            ref = "%.2g: " % same[3] if len(same) >= 4 else ""
            cells.append("%s%s%s" % (ref, fmt_dev(same), " [%s]" % fmt_dev(noise) if noise[1] else ""))
        add("| %s | %s |" % (feat, " | ".join(cells)))
    add("")
    return L


def rule_counts(runs):
    out = {}
    for r in runs:
        for c in r["contradictions"]:
            rule = c["rule"].split(" (")[0]
            out[rule] = out.get(rule, 0) + 1
    return out


def fmt_dev(d):
    v, where = d[0], d[1]
    if where is None:
        return "–"
    if len(d) >= 3:  # absolute deviation first: relative ones mislead near a reference of 0
        rel = "∞" if v == float("inf") else "%.0f%%" % (100 * v)
        return "±%.2g (%s) %s" % (d[2], rel, short(where))
    if v == float("inf"):
        return "∞ (%s)" % where
    return "%.0f%% %s" % (100 * v, short(where))


def short(name):
    return "@" + name.replace(" seed ", "/s").replace(" faces", "").replace("level ", "L").replace("noise ", "I")


def write_results(path, lines):
    replace_section(path, BEGIN, END, lines)


# ---- the tiny run's checks (ctest bench_words_tiny) --------------------------------------------
def check_tiny(runs, cfg):
    problems = []
    for r in runs:
        want = ["letter"] if r["group"] == "inscription" else list(SPHERE_KINDS)
        if r["group"] == "engraved":
            want += [k + " (engraved)" for k in SPHERE_KINDS]
        for kind in want:
            if kind not in r["kinds"]:
                problems.append("%s: no texel covers a %s" % (r["name"], kind))
        for c in r["contradictions"]:
            problems.append("%s: texture %s (%s): %s: %s" % (r["name"], c["texture"], c["kind"], c["rule"],
                                                            " + ".join(c["labels"])))
        if r["convex_on_engraved"]:
            problems.append("%s: %d texels of engraved shapes in textures with a convex word" % (r["name"],
                                                                                                r["convex_on_engraved"]))
        for kind, k in r["kinds"].items():
            for c in k["concept_details"]:
                if not isinstance(c.get("label"), str) or not c["label"]:
                    problems.append("%s: %s: a concept without a label: %s" % (r["name"], kind, c))
    return problems


# ---- main --------------------------------------------------------------------------------------
def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="build directory (default: build)")
    ap.add_argument("--geotex", help="geotex command (default: BUILD/geotex)")
    ap.add_argument("--simplify", help="geotex_simplify (default: BUILD/geotex_simplify)")
    ap.add_argument("--out", help="work directory (default: out/bench-words; --tiny: a temporary one)")
    ap.add_argument("--results", default=os.path.join(ROOT, "bench", "RESULTS.md"), help="results file to update")
    ap.add_argument("--tiny", action="store_true", help="levels 5 and 6, a few conditions, checked; writes nothing")
    ap.add_argument("--keep", action="store_true", help="keep the meshes, reports and segmentations")
    ap.add_argument("--from-json", dest="from_json", help="no runs: rewrite RESULTS.md from a saved results.json")
    ap.add_argument("--before", help="results.json of an earlier geotex, shown beside the targets")
    ap.add_argument("--annotate-option", action="append", metavar="ARG",
                    help="one more argument of every geotex annotate (repeat it: --annotate-option=--concepts "
                         "--annotate-option=5), to compare choice options (with --results elsewhere)")
    ap.add_argument("--only", action="append", help="run only the conditions whose name contains this (no RESULTS.md update)")
    args = ap.parse_args()
    args.geotex = args.geotex or os.path.join(args.build, "geotex")
    args.simplify = args.simplify or os.path.join(args.build, "geotex_simplify")
    before = None
    if args.before:
        with open(args.before) as f:
            before = json.load(f)
    if args.from_json:
        with open(args.from_json) as f:
            saved = json.load(f)
        write_results(args.results, make_markdown(saved["results"], saved["meta"], before))
        print("rewrote the words section of %s from %s" % (args.results, args.from_json))
        return 0
    for exe in (args.geotex, args.simplify):
        if not os.access(exe, os.X_OK):
            sys.exit("words: %s is missing: build first (make build)" % exe)
    cfg = TINY if args.tiny else FULL
    conds = cfg["conditions"]
    if args.only:
        conds = [c for c in conds if c["name"] == cfg["reference"] or any(o in c["name"] for o in args.only)]
    tmp = tempfile.mkdtemp(prefix="geotex-words-") if args.tiny else None
    out = tmp or args.out or os.path.join(ROOT, "out", "bench-words")
    if os.path.isdir(out) and not args.tiny:
        shutil.rmtree(out)
    os.makedirs(out, exist_ok=True)
    runner = Runner(args, cfg, out)
    try:
        runs = []
        for cond in conds:
            r = runner.condition(cond)
            runs.append(r)
            print("[words] %-18s %9s faces  texels %3d  textures %2d  contradictions %2d  %s  (%.1f s)" % (
                r["name"], "{:,}".format(r["faces"]), r["texels"], r["textures"], len(r["contradictions"]),
                "; ".join("%s: %s" % (k, ", ".join(v["concepts"])) for k, v in r["kinds"].items()), r["seconds"]),
                flush=True)
        seconds = time.time() - runner.started
        src = source_of(args.geotex)
        meta = {"command": "make bench" if not args.tiny else "words.py --tiny",
                "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
                "nproc": len(os.sched_getaffinity(0)), "commit": git_commit(ROOT), "geotex_commit": git_commit(src),
                "seconds": seconds}
        results = {"config": {"scale": cfg["scale"], "reference": cfg["reference"]}, "runs": runs}
        with open(os.path.join(out, "results.json"), "w") as f:
            json.dump({"meta": meta, "results": results}, f, indent=1)
        if not args.keep:
            # The meshes and truths kept for the conditions derived from the reference.
            for name in os.listdir(out):
                if name != "results.json":
                    os.remove(os.path.join(out, name))
        if args.tiny:
            problems = check_tiny(runs, cfg)
            for p in problems:
                print("FAIL: " + p)
            print("tiny words experiment: %s in %.1f s" % ("FAILED" if problems else "ok", seconds))
            return 1 if problems else 0
        if args.only:
            print("partial run in %.0f s: %s/results.json; RESULTS.md unchanged" % (seconds, out))
            return 0
        write_results(args.results, make_markdown(results, meta, before))
        print("words experiment done in %.0f s: wrote %s (results: %s/results.json)" % (seconds, args.results, out))
        return 0
    finally:
        if tmp:
            shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
