#!/usr/bin/env python3
"""The ground truth of bench/experiments/inscription.py is coherent with its mesh (issue 20,
item 5): the scale cases are scored against it, so a wrong truth would score geotex wrongly.

    tests/inscription_test.py GEOTEX SOURCE_DIR

Each scale case (short, long, mixed) is made at a coarse spacing into a temporary directory
and read back from the files geotex reads: the truth names as many faces as the PLY; shape
ids run 0, 1, 2, ...; the cases hold the details issue 20 names (16 and 31; mixed 26); every
shape has faces; letters are engraved and bosses raised, measured on the mesh itself (radial
offsets from the cylinder); the same options give the same bytes; and `geotex evaluate` scores a
segmentation made from the truth itself as every shape matched, none spurious. The words
case keeps its 11 letters, no bosses and its old truth keys (words.py's input).
"""

import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import unittest

GEOTEX = SOURCE = None
RADIUS = 2.0  # inscription.py's cylinder: axis x = 0, z = -RADIUS, along y
# Coarse, so that the whole test takes a few seconds, yet fine enough that the narrowest
# groove (long and mixed: half-width 0.005 where the grey exceeds 0.5) holds faces.
SPACING = {"short": 0.01, "long": 0.005, "mixed": 0.005}
DETAILS = {"short": (8, 8), "long": (27, 4), "mixed": (22, 4)}  # (letters, bosses)


def read_ply(path):
    """Vertices (list of (x, y, z)) and triangles of inscription.py's binary PLY."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    nv = int(next(l for l in header if l.startswith("element vertex")).split()[2])
    nf = int(next(l for l in header if l.startswith("element face")).split()[2])
    verts = list(struct.iter_unpack("<3d", data[end:end + 24 * nv]))
    faces = [t[1:] for t in struct.iter_unpack("<B3i", data[end + 24 * nv:end + 24 * nv + 13 * nf])]
    return header, verts, faces


def radial(p):
    """Height above the cylinder of radius RADIUS: positive raised, negative engraved."""
    return math.hypot(p[0], p[2] + RADIUS) - RADIUS


def generate(tmp, case, spacing, name=None, extra=()):
    name = name or case
    mesh, truth = os.path.join(tmp, name + ".ply"), os.path.join(tmp, name + ".truth.json")
    subprocess.run([sys.executable, os.path.join(SOURCE, "bench", "experiments", "inscription.py"), mesh, truth,
                    "--case", case, "--spacing", repr(spacing), *extra], check=True, stdout=subprocess.DEVNULL)
    return mesh, truth


class ScaleCases(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory(prefix="geotex-inscription-")
        cls.made = {}
        for case, spacing in SPACING.items():
            mesh, truth = generate(cls.tmp.name, case, spacing)
            with open(truth) as f:
                t = json.load(f)
            cls.made[case] = (mesh, truth, read_ply(mesh), t)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_truth_matches_mesh_and_ids(self):
        for case, (_, _, (header, verts, faces), t) in self.made.items():
            with self.subTest(case=case):
                self.assertEqual(len(t["face_shape"]), len(faces))
                self.assertEqual(t["mesh"], {"file": case + ".ply", "vertices": len(verts), "faces": len(faces)})
                self.assertEqual([s["id"] for s in t["shapes"]], list(range(len(t["shapes"]))))
                letters = [s for s in t["shapes"] if s["kind"] == "letter"]
                bosses = [s for s in t["shapes"] if s["kind"] == "boss"]
                self.assertEqual((len(letters), len(bosses)), DETAILS[case])
                self.assertEqual(len(letters) + len(bosses), len(t["shapes"]))
                self.assertTrue(all(s["engraved"] for s in letters))
                self.assertFalse(any(s["engraved"] for s in bosses))
                self.assertTrue(all(-1 <= k < len(t["shapes"]) for k in t["face_shape"]))
                self.assertEqual(t["parameters"]["case"], case)
                self.assertTrue(any(l.startswith("comment geotex inscription: case " + case) for l in header))

    def test_every_shape_has_faces(self):
        for case, (_, _, _, t) in self.made.items():
            with self.subTest(case=case):
                count = [0] * len(t["shapes"])
                for k in t["face_shape"]:
                    if k >= 0:
                        count[k] += 1
                empty = [t["shapes"][i].get("glyph", "boss %d" % i) for i, c in enumerate(count) if c == 0]
                self.assertEqual(empty, [], "shapes without faces")

    def test_bosses_raised_letters_engraved(self):
        for case, (_, _, (_, verts, faces), t) in self.made.items():
            fs = t["face_shape"]
            # Per shape: the mean radial offset of the vertices of its faces, and of the
            # background vertices (faces of no shape) near it, so that the broad swellings and
            # hollows of the relief cancel out.
            inside = {}
            for f, k in zip(faces, fs):
                if k >= 0:
                    inside.setdefault(k, set()).update(f)
            background = set()
            for f, k in zip(faces, fs):
                if k < 0:
                    background.update(f)
            grid = {}  # background vertices by cells of 0.05, to find those near a shape
            for i in background:
                p = verts[i]
                grid.setdefault((int(math.floor(p[0] / 0.05)), int(math.floor(p[1] / 0.05))), []).append(i)
            for k, shape in enumerate(t["shapes"]):
                with self.subTest(case=case, shape=k, kind=shape["kind"]):
                    pts = [verts[i] for i in inside[k]]
                    cx = sum(p[0] for p in pts) / len(pts)
                    cy = sum(p[1] for p in pts) / len(pts)
                    reach = 0.05 + 2 * max(math.hypot(p[0] - cx, p[1] - cy) for p in pts) if shape["kind"] == "boss" \
                        else 0.06
                    near = [verts[i] for (gx, gy), ids in grid.items()
                            if abs((gx + 0.5) * 0.05 - cx) < reach + 0.05 and abs((gy + 0.5) * 0.05 - cy) < reach + 0.05
                            for i in ids if math.hypot(verts[i][0] - cx, verts[i][1] - cy) < reach]
                    self.assertGreater(len(near), 10)
                    ground = sum(radial(p) for p in near) / len(near)
                    if shape["kind"] == "boss":
                        # At its centre a boss stands its height (worn to 0.65 at worst) above
                        # the stone; half of that leaves room for the relief and the noise.
                        top = min(verts, key=lambda p: (p[0] - shape["center"][0]) ** 2 + (p[1] - shape["center"][1]) ** 2
                                  + (p[2] - shape["center"][2]) ** 2)
                        self.assertGreater(radial(top) - ground, 0.5 * 0.65 * shape["height"])
                    else:
                        # The faces of a letter lie where its groove is deeper than half its
                        # depth (grey > 0.5), worn to 0.65 at worst: a quarter is a safe bound.
                        low = sum(radial(p) for p in pts) / len(pts)
                        self.assertLess(low - ground, -0.25 * 0.65 * shape["depth"])

    def test_same_options_same_bytes(self):
        mesh, truth, _, _ = self.made["short"]
        mesh2, truth2 = generate(self.tmp.name, "short", SPACING["short"], name="short-again")
        for a, b in ((mesh, mesh2), (truth, truth2)):
            with open(a, "rb") as fa, open(b, "rb") as fb:
                da, db = fa.read(), fb.read()
            if a == truth:  # the truth names its mesh file
                da, db = da.replace(b"short.ply", b""), db.replace(b"short-again.ply", b"")
            self.assertEqual(da, db)

    def test_noise_moves_no_detail(self):
        # The noise has its own generator: without it the truth is the same.
        _, truth, _, t = self.made["short"]
        _, quiet = generate(self.tmp.name, "short", SPACING["short"], name="short-quiet", extra=("--noise", "0"))
        with open(quiet) as f:
            self.assertEqual(json.load(f)["face_shape"], t["face_shape"])

    def test_words_case_unchanged(self):
        _, truth = generate(self.tmp.name, "words", 0.02)
        with open(truth) as f:
            t = json.load(f)
        self.assertEqual(len(t["shapes"]), 11)
        self.assertEqual({s["kind"] for s in t["shapes"]}, {"letter"})
        self.assertEqual(sorted(t["parameters"]), ["height", "lines", "radius", "seed", "spacing", "wear", "width"])

    def test_evaluate_scores_the_truth_itself_perfect(self):
        # A segmentation PLY whose texels are the truth's shapes and whose textures are its
        # kinds: geotex evaluate must read the truth and find every shape matched.
        mesh, truth, (_, verts, faces), t = self.made["mixed"]
        kinds = sorted({s["kind"] for s in t["shapes"]})
        seg = os.path.join(self.tmp.name, "mixed.truth-seg.ply")
        with open(seg, "wb") as out:
            out.write(("ply\nformat binary_little_endian 1.0\nelement vertex %d\nproperty double x\n"
                       "property double y\nproperty double z\nelement face %d\nproperty list uchar int vertex_indices\n"
                       "property int texel\nproperty int texture\nend_header\n" % (len(verts), len(faces))).encode())
            out.write(b"".join(struct.pack("<3d", *p) for p in verts))
            out.write(b"".join(struct.pack("<B3i2i", 3, *f, k, kinds.index(t["shapes"][k]["kind"]) if k >= 0 else -1)
                               for f, k in zip(faces, t["face_shape"])))
        scores = os.path.join(self.tmp.name, "scores.json")
        subprocess.run([GEOTEX, "evaluate", seg, truth, "--json", scores, "--quiet"], check=True,
                       stdout=subprocess.DEVNULL)
        with open(scores) as f:
            s = json.load(f)
        n = len(t["shapes"])
        self.assertEqual((s["shapes"], s["matched"], s["split"], s["missed"], s["spurious"]), (n, n, 0, 0, 0))
        self.assertAlmostEqual(s["ari_kind"], 1.0)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: inscription_test.py GEOTEX SOURCE_DIR")
    GEOTEX, SOURCE = sys.argv[1], sys.argv[2]
    unittest.main(argv=sys.argv[:1], verbosity=2)
