#!/usr/bin/env python3
"""Writes the malformed-input corpus of tests/corpus_test.sh into the current directory.

Every file is built here from a small valid mesh or dictionary and then broken in one way,
so that each case tests one problem. Standard library only; the output is deterministic.
"""
import json
import math
import random
import re
import struct

# A tetrahedron: the smallest closed mesh.
V = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def write(name, data):
    with open(name, "wb") as f:
        f.write(data.encode("utf-8") if isinstance(data, str) else data)


# ---- PLY -------------------------------------------------------------------------------------

def ply_header(fmt, nv, nf, vertex_type="float", xyz=("x", "y", "z"), face_prop="property list uchar int vertex_indices"):
    lines = ["ply", "format " + fmt + " 1.0", "element vertex %s" % nv]
    lines += ["property %s %s" % (vertex_type, a) for a in xyz]
    lines += ["element face %s" % nf, face_prop, "end_header"]
    return "\n".join(lines) + "\n"


def ply_ascii(verts=V, faces=F, nv=None, nf=None, **header):
    nv = len(verts) if nv is None else nv
    nf = len(faces) if nf is None else nf
    body = "".join("%s %s %s\n" % tuple(v) for v in verts)
    body += "".join("%d %s\n" % (len(f), " ".join(str(i) for i in f)) for f in faces)
    return ply_header("ascii", nv, nf, **header) + body


def ply_binary(big, verts=V, faces=F, nv=None, nf=None, vfmt="f", ifmt="i"):
    nv = len(verts) if nv is None else nv
    nf = len(faces) if nf is None else nf
    e = ">" if big else "<"
    vtype = {"f": "float", "d": "double"}[vfmt]
    itype = {"i": "int", "f": "float", "I": "uint"}[ifmt]
    head = ply_header("binary_big_endian" if big else "binary_little_endian", nv, nf, vertex_type=vtype,
                      face_prop="property list uchar %s vertex_indices" % itype)
    body = b"".join(struct.pack(e + vfmt * 3, *v) for v in verts)
    body += b"".join(struct.pack(e + "B" + ifmt * len(f), len(f), *f) for f in faces)
    return head.encode() + body


# Unbroken files from the same helpers: they must read, so each error below comes from the
# one thing broken.
write("good_ascii.ply", ply_ascii())
write("good_binary_le.ply", ply_binary(False))
write("good_binary_be.ply", ply_binary(True, vfmt="d"))
write("ply_ascii_fewer_vertices.ply", ply_ascii(verts=V[:3], nv=4))
write("ply_ascii_more_vertices.ply", ply_ascii(verts=V + [(1.0, 1.0, 1.0)], nv=4))
write("ply_ascii_fewer_faces.ply", ply_ascii(faces=F[:3], nf=4))
write("ply_ascii_more_faces.ply", ply_ascii(faces=F + [(0, 1, 2)], nf=4))
write("ply_binary_le_fewer_faces.ply", ply_binary(False, faces=F[:3], nf=4))
write("ply_binary_be_fewer_vertices.ply", ply_binary(True, verts=V[:3], nv=4))
write("ply_binary_le_more_faces.ply", ply_binary(False, faces=F + [(0, 1, 2)], nf=4))
write("ply_binary_le_more_vertices.ply", ply_binary(False, verts=V + [(1.0, 1.0, 1.0)], nv=4))
write("ply_header_only.ply", ply_header("ascii", 4, 4))
write("ply_binary_header_only.ply", ply_header("binary_little_endian", 4, 4))
whole = ply_ascii()
write("ply_mid_header.ply", whole[: whole.index("element face")])
binary = ply_binary(True)
write("ply_binary_be_mid_body.ply", binary[: len(binary) - 23])
write("ply_float_indices.ply", ply_binary(False, ifmt="f"))
write("ply_unknown_type.ply", ply_ascii(vertex_type="flaot"))
write("ply_missing_z.ply", ply_ascii(verts=[v[:2] + ("",) for v in V], xyz=("x", "y")).replace(" \n", "\n"))
write("ply_index_out_of_range.ply", ply_ascii(faces=F[:3] + [(1, 2, 4)]))
write("ply_negative_index.ply", ply_ascii(faces=F[:3] + [(1, -2, 3)]))
write("ply_binary_le_index_out_of_range.ply", ply_binary(False, faces=F[:3] + [(1, 2, 7)]))
write("ply_binary_be_negative_index.ply", ply_binary(True, faces=F[:3] + [(1, 2, -1)]))
write("ply_binary_uint_index_wraps.ply", ply_binary(False, faces=F[:3] + [(1, 2, 0xFFFFFFFF)], ifmt="I"))
write("ply_nan.ply", ply_ascii(verts=[V[0], (1.0, "nan", 0.0)] + V[2:]))
write("ply_inf.ply", ply_ascii(verts=V[:3] + [(0.0, 0.0, "-inf")]))
write("ply_binary_le_nan.ply", ply_binary(False, verts=V[:2] + [(0.0, math.nan, 0.0)] + V[3:]))
write("ply_binary_be_inf.ply", ply_binary(True, verts=V[:3] + [(math.inf, 0.0, 1.0)], vfmt="d"))
write("ply_ascii_huge_faces.ply", ply_ascii(nf=10**12))
write("ply_binary_le_huge_faces.ply", ply_binary(False, nf=10**12))
write("ply_binary_be_huge_vertices.ply", ply_binary(True, nv=10**12))
write("ply_count_overflow.ply", ply_ascii(nf=10**30))
rng = random.Random(20261126)
write("ply_ascii_garbage_body.ply", ply_header("ascii", 4, 4) + "".join(rng.choice("abcxyz#!?") for _ in range(200)) + "\n")
write("ply_binary_garbage_body.ply", ply_header("binary_little_endian", 4, 4).encode() + bytes([0xFF] * 12 + [rng.randrange(256) for _ in range(96)]))
write("ply_bad_magic.ply", "plx\n" + whole[4:])
write("ply_empty.ply", b"")
write("ply_zero_faces.ply", ply_ascii(faces=[]))
write("ply_zero_vertices.ply", ply_ascii(verts=[], faces=[]))
write("ply_all_degenerate.ply", ply_ascii(verts=[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (2.0, 0.0, 0.0), (3.0, 0.0, 0.0)],
                                          faces=[(0, 1, 2), (1, 2, 3), (0, 0, 1), (3, 3, 3)]))
write("ply_two_corner_face.ply", ply_ascii(faces=F[:3] + [(1, 2)]))
write("ply_bad_format.ply", whole.replace("format ascii", "format binary_middle_endian"))
write("ply_vertex_list.ply", whole.replace("property float z", "property list uchar float z"))
write("ply_no_end_header.ply", whole.replace("end_header\n", ""))

# ---- OBJ -------------------------------------------------------------------------------------

def obj(verts=V, faces=[tuple(i + 1 for i in f) for f in F]):
    return "".join("v %s %s %s\n" % tuple(v) for v in verts) + "".join("f %s\n" % " ".join(str(i) for i in f) for f in faces)


write("good.obj", obj())
write("obj_short_vertex.obj", "v 0 0\n" + obj())
write("obj_bad_number.obj", obj(verts=V[:1] + [(1.0, "1.0.0", 0.0)] + V[2:]))
write("obj_index_zero.obj", obj(faces=[(1, 2, 3), (0, 2, 3)]))
write("obj_index_beyond.obj", obj(faces=[(1, 2, 3), (1, 2, 5)]))
write("obj_relative_out_of_range.obj", obj(faces=[(1, 2, 3), (-1, -2, -5)]))
write("obj_nan.obj", obj(verts=V[:2] + [(0.0, "NaN", 0.0)] + V[3:]))
write("obj_unknown_statement.obj", "vx 1 2 3\n" + obj())
write("obj_no_faces.obj", obj(faces=[]))
write("obj_empty.obj", b"")
write("good_bom.obj", b"\xef\xbb\xbf" + obj().encode())  # a byte order mark, as Windows editors write

# ---- OFF -------------------------------------------------------------------------------------

def off(verts=V, faces=F, nv=None, nf=None, keyword="OFF\n"):
    nv = len(verts) if nv is None else nv
    nf = len(faces) if nf is None else nf
    return (keyword + "%s %s 0\n" % (nv, nf) + "".join("%s %s %s\n" % tuple(v) for v in verts)
            + "".join("%d %s\n" % (len(f), " ".join(str(i) for i in f)) for f in faces))


write("good.off", off())
write("off_fewer_vertices.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n")
write("off_fewer_faces.off", off(faces=F[:2], nf=4))
write("off_truncated.off", off()[:-9])
write("off_missing_header.off", off(keyword=""))
write("off_negative_count.off", off(nv=-4))
write("off_index_out_of_range.off", off(faces=F[:3] + [(1, 2, 9)]))
write("off_huge_counts.off", off(nv=2**31 - 1, nf=2**31 - 1))
write("off_count_too_large.off", off(nf=10**12))
write("off_more_faces.off", off(faces=F + [(0, 1, 2)], nf=4))
write("off_empty.off", b"")
write("good_bom.off", b"\xef\xbb\xbf" + off().encode())

# ---- STL -------------------------------------------------------------------------------------

def stl_ascii(faces=F):
    out = "solid t\n"
    for f in faces:
        out += "facet normal 0 0 0\nouter loop\n" + "".join("vertex %s %s %s\n" % V[i] for i in f)
        out += "endloop\nendfacet\n"
    return out + "endsolid t\n"


def stl_binary(count=None, faces=F, corner=None):
    head = b"geotex corpus".ljust(80, b" ") + struct.pack("<I", len(faces) if count is None else count)
    body = b""
    for f in faces:
        pts = [V[i] for i in f]
        if corner is not None and f is faces[-1]:
            pts[0] = corner
        body += struct.pack("<12fH", 0, 0, 0, *pts[0], *pts[1], *pts[2], 0)
    return head + body


write("good_ascii.stl", stl_ascii())
write("good_binary.stl", stl_binary())
write("stl_ascii_truncated.stl", stl_ascii()[:-60])
write("stl_ascii_two_corners.stl", re.sub(r"vertex [^\n]*\nendloop", "endloop", stl_ascii(), count=1))
write("stl_binary_count_mismatch.stl", stl_binary(count=100))
write("stl_binary_huge_count.stl", stl_binary(count=0xFFFFFFFF))
write("stl_no_facets.stl", "solid empty\nendsolid empty\n")
write("stl_binary_nan.stl", stl_binary(corner=(math.nan, 0.0, 0.0)))
write("stl_short.stl", b"\x00" * 40)

# ---- dictionaries ----------------------------------------------------------------------------

HEAD = """scheme:
  id: corpus
  version: "1"
  namespace: "https://example.org/dict/corpus/"
  languages: [en]
  title: {en: Corpus}
features:
"""


def dictionary(body):
    return HEAD + body


GOOD = """  contour_sphericity:
    - id: circular
      interval: [0, 0.1]
      labels: {en: circular}
    - id: oval
      interval: [0.1, 0.3]
      labels: {en: oval}
"""
write("dict_good.yaml", dictionary(GOOD))
write("dict_wrong_type.yaml", dictionary(GOOD.replace("[0.1, 0.3]", "[low, 0.3]")))
write("dict_overlap.yaml", dictionary(GOOD.replace("[0.1, 0.3]", "[0.05, 0.3]")))
write("dict_unknown_key.yaml", dictionary(GOOD.replace("labels: {en: oval}", "lables: {en: oval}")))
write("dict_unknown_feature.yaml", dictionary(GOOD.replace("contour_sphericity", "contour_sphericty")))
write("dict_lower_above_upper.yaml", dictionary(GOOD.replace("[0.1, 0.3]", "[0.3, 0.1]")))
write("dict_invalid_utf8.yaml", dictionary(GOOD).encode().replace(b"{en: oval}", b"{en: ov\xc3\x28l}"))
write("dict_latin1.yaml", dictionary(GOOD.replace("oval}", "ovale allong\u00e9e}")).encode("latin-1"))
write("dict_syntax_error.yaml", dictionary(GOOD.replace("[0.1, 0.3]", "[0.1, 0.3")))
write("dict_interval_scalar.yaml", dictionary(GOOD.replace("[0.1, 0.3]", "0.3")))
write("dict_empty.yaml", b"")
# 55 significant digits: above 0.1 as a decimal (so it overlaps [0.1, 0.3)), 0.1 as a double.
write("dict_bound_digits.yaml", dictionary(GOOD.replace("[0, 0.1]", "[0, 0.1" + "0" * 53 + "1]")))
# Escape and control characters in a key (YAML's double-quoted escapes): clear the screen,
# ring the bell, start a new line. The messages must show them, not send them.
write("dict_control_key.yaml", dictionary(GOOD.replace("contour_sphericity:", '"contour\\e[2J\\a\\nsphericity":')))

# Facets (a texture gets at most one concept per facet) and relief.
FACETS = """facets:
  outline:
    labels: {en: outline}
    features: [contour_sphericity]
"""


def faceted(body, facets=FACETS):
    return HEAD.replace("features:\n", facets + "features:\n") + body


write("dict_facets_good.yaml", faceted(GOOD))
write("dict_duplicate_label.yaml", faceted(GOOD.replace("{en: oval}", "{en: circular}")))
write("dict_feature_in_no_facet.yaml", faceted(GOOD, FACETS.replace("[contour_sphericity]", "[area]")))
write("dict_feature_in_two_facets.yaml",
      faceted(GOOD, FACETS + "  roundness:\n    labels: {en: roundness}\n    features: [contour_sphericity]\n"))
write("dict_facet_unknown_feature.yaml",
      faceted(GOOD, FACETS.replace("[contour_sphericity]", "[contour_sphericity, contour_sphericty]")))
write("dict_facet_no_features.yaml", faceted(GOOD, FACETS.replace("[contour_sphericity]", "[]")))
write("dict_facet_label_missing.yaml", faceted(GOOD, FACETS.replace("{en: outline}", "{fr: contour}")))
write("dict_facet_unknown_key.yaml", faceted(GOOD, FACETS.replace("    labels:", "    lables:")))
write("dict_unknown_relief.yaml", faceted(GOOD.replace("{en: oval}\n", "{en: oval}\n      relief: convex\n")))

# ---- segmentations and ground truths for `geotex evaluate` -------------------------------

SEG = ("ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 4\nproperty list uchar int vertex_indices\nproperty int texel\nproperty int texture\nend_header\n"
       + "".join("%s %s %s\n" % v for v in V) + "".join("3 %d %d %d 0 0\n" % f for f in F))
write("seg.ply", SEG)
write("seg_no_texel.ply", ply_ascii())
write("truth_good.json", json.dumps({"shapes": [{"id": 0, "kind": "disc"}], "face_shape": [0, 0, -1, -1]}))
write("truth_face_count.json", json.dumps({"shapes": [{"id": 0, "kind": "disc"}], "face_shape": [0, -1]}))
write("truth_shape_range.json", json.dumps({"shapes": [{"id": 0, "kind": "disc"}], "face_shape": [0, 7, -1, -5]}))
write("truth_syntax.json", '{"shapes": [{"id": 0,\n "kind": "disc"}\n oops')
write("truth_wrong_type.json", json.dumps({"shapes": [{"id": "zero", "kind": "disc"}], "face_shape": [0, 0, -1, -1]}))
