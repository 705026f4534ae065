"""geotex.annotate and geotex.annotate_file against `geotex annotate`: the same bytes of
Turtle, N-Triples and JSON-LD, the same words as the JSON report, and the command's refusals."""

import json
import subprocess

import pytest

import geotex
from conftest import run

SCALE = 0.04


@pytest.fixture(scope="session")
def annotated(command, sphere6, work):
    """sphere6 annotated by the command: Turtle, N-Triples (a second run), JSON-LD, report."""
    out = {}
    for fmt, ext in (("turtle", "ttl"), ("ntriples", "nt")):
        path = work / f"sphere6.{ext}"
        extra = ["--jsonld", work / "sphere6.jsonld", "--json", work / "sphere6.json"] if ext == "ttl" else []
        code, _, err = run(command, "annotate", sphere6, "--scale", SCALE, "--format", fmt, "-o", path,
                           "-q", *extra)
        assert code == 0, err
        out[ext] = path.read_text()
    out["jsonld"] = (work / "sphere6.jsonld").read_text()
    out["report"] = json.loads((work / "sphere6.json").read_text())
    return out


def test_a_file_gives_the_command_s_bytes(sphere6, annotated):
    a = geotex.annotate_file(str(sphere6), scale=SCALE)
    assert a.to_turtle() == annotated["ttl"]
    assert a.to_ntriples() == annotated["nt"]
    assert a.to_jsonld() == annotated["jsonld"]


def test_the_words_are_the_json_report_s(sphere6, annotated):
    a = geotex.annotate_file(str(sphere6), scale=SCALE)
    report = annotated["report"]["annotation"]["textures"]
    assert len(a.textures) == len(report) == 4
    for mine, theirs in zip(a.textures, report):
        assert mine["texture"] == theirs["texture"]
        assert mine["num_texels"] == theirs["texels"]
        assert mine["orientation"] == theirs["orientation"]
        assert mine["concepts"] == [c["concept"] for c in theirs["concepts"]]
        assert mine["label"] == ", ".join(c["label"] for c in theirs["concepts"])
        assert mine["withheld"] == [c["concept"] for c in theirs["withheld"]]
        assert mine["note"] == theirs.get("note", "")
        for c in theirs["concepts"]:
            f = mine["features"][c["feature"]]
            assert (f["concept"], f["value"], f["significance"], f["agreement"], f["stability"]) == (
                c["concept"], c["value"], c["significance"], c["agreement"], c["stability"])
        assert list(mine["features"]) and set(mine["features"]) <= set(a.segmentation.feature_names)
    assert a.segmentation.num_textures == 4


def test_arrays_are_named_by_their_ply_and_give_the_command_s_bytes(command, sphere6, work):
    # The synthetic PLY without its header comment is exactly the binary PLY that the library
    # writes for these arrays, so the command names it by the same digest.
    data = sphere6.read_bytes()
    start = data.index(b"comment")
    plain = work / "plain6.ply"
    plain.write_bytes(data[:start] + data[data.index(b"\n", start) + 1:])
    ttl = work / "plain6.ttl"
    code, _, err = run(command, "annotate", plain, "--scale", SCALE, "-o", ttl, "-q")
    assert code == 0, err
    V, F = geotex.read_mesh(str(plain))
    from_arrays = geotex.annotate(V, F, scale=SCALE, name="plain6.ply")
    assert from_arrays.to_turtle() == ttl.read_text()
    # A segmentation given as it is: the same annotation, no new segmentation.
    seg = geotex.segment(V, F, scale=SCALE)
    again = geotex.annotate(seg, name="plain6.ply")
    assert again.segmentation is seg
    assert again.to_turtle() == from_arrays.to_turtle()


def test_options_reach_the_rdf_as_the_command_s(command, sphere6, work):
    options = dict(label_language="fr", base="https://example.org/object/7/", object="https://example.org/object/7",
                   creator="https://example.org/people/curator", mesh_unit="mm",
                   timestamp="2026-11-25T18:00:00Z", min_agreement=0.6, resamples=50)
    ttl = work / "options6.ttl"
    code, _, err = run(command, "annotate", sphere6, "--scale", SCALE, "-o", ttl, "-q", "--lang", "fr",
                       "--base", options["base"], "--object", options["object"], "--creator",
                       options["creator"], "--mesh-unit", "mm", "--timestamp", options["timestamp"],
                       "--min-agreement", 0.6, "--resamples", 50)
    assert code == 0, err
    a = geotex.annotate_file(str(sphere6), scale=SCALE, **options)
    assert a.to_turtle() == ttl.read_text()
    assert "https://example.org/object/7/mesh" in a.to_turtle()


def test_a_dictionary_as_a_path_or_as_text(sphere6):
    from conftest import SOURCE_DIR
    default = SOURCE_DIR / "dictionaries" / "default.yaml"
    built_in = geotex.annotate_file(str(sphere6), scale=SCALE)
    by_path = geotex.annotate_file(str(sphere6), scale=SCALE, dictionary=str(default))
    by_text = geotex.annotate_file(str(sphere6), scale=SCALE, dictionary=default.read_text())
    assert [t["concepts"] for t in by_path.textures] == [t["concepts"] for t in built_in.textures]
    assert [t["concepts"] for t in by_text.textures] == [t["concepts"] for t in built_in.textures]


def test_refusals_are_the_command_s_classes(sphere6, work):
    seg = geotex.segment(*geotex.read_mesh(str(sphere6)), scale=SCALE)
    with pytest.raises(geotex.InputError, match=r"<dictionary text>:3:1"):
        geotex.annotate(seg, dictionary="version: 1\nfoo: [\n")
    with pytest.raises(geotex.IoError, match="missing.yaml"):
        geotex.annotate(seg, dictionary=str(work / "missing.yaml"))
    for bad in (dict(base="not an iri"), dict(object="urn with space"), dict(mesh_unit="furlong"),
                dict(label_language="english!"), dict(timestamp="yesterday"), dict(min_agreement=0.0),
                dict(resamples=-1)):
        with pytest.raises(geotex.UsageError):
            geotex.annotate(seg, **bad)
    with pytest.raises(geotex.UsageError, match="no F"):
        geotex.annotate(seg, scale=SCALE)
    with pytest.raises(geotex.UsageError):
        geotex.annotate(seg.V)


def test_to_json_is_the_command_s_report(command, sphere6, work, annotated):
    a = geotex.annotate_file(str(sphere6), scale=SCALE)
    assert a.to_json() == (work / "sphere6.json").read_text()
    # The segmentation alone: the report of `geotex segment --json`.
    seg_json = work / "sphere6.segment.json"
    code, _, err = run(command, "segment", sphere6, "--scale", SCALE, "-o", work / "sphere6.seg.ply",
                       "--json", seg_json, "-q")
    assert code == 0, err
    assert a.segmentation.to_json() == seg_json.read_text()


def test_a_file_that_needs_repair_is_read_once_and_reported_as_the_command_does(command, engraved5, work):
    # An OBJ of the engraved sphere with one vertex given twice and one face given twice: the
    # report's input counts what the repair of the file did, as the command's does.
    V, F = geotex.read_mesh(str(engraved5))
    obj = work / "repair5.obj"
    with open(obj, "w") as out:
        for x, y, z in V:
            out.write(f"v {x!r} {y!r} {z!r}\n")
        out.write(f"v {V[0][0]!r} {V[0][1]!r} {V[0][2]!r}\n")
        for a, b, c in F:
            out.write(f"f {a + 1} {b + 1} {c + 1}\n")
        out.write(f"f {F[0][0] + 1} {F[0][1] + 1} {F[0][2] + 1}\n")
    report = work / "repair5.json"
    options = ["--scale", 0.05, "--orientation", "both"]
    code, _, err = run(command, "annotate", obj, *options, "-o", work / "repair5.ttl", "--json", report, "-q")
    assert code == 0, err
    a = geotex.annotate_file(str(obj), scale=0.05, orientation="both")
    assert a.to_json() == report.read_text()
    assert a.to_turtle() == (work / "repair5.ttl").read_text()
    repair = json.loads(a.to_json())["input"]
    assert (repair["format"], repair["input_vertices"], repair["input_polygons"]) == ("obj", len(V) + 1, len(F) + 1)
    assert repair["repair"]["duplicate_faces_removed"] == 1
    assert repair["repair"]["duplicate_vertices_merged"] == 1
    # The segmentation's arrays are the repaired file's: one face per row of the OBJ kept.
    assert a.segmentation.F.shape == F.shape
    assert a.segmentation.repair["duplicate_faces_removed"] == 1


def test_arrays_report_names_the_file_given(command, sphere6, work):
    # As in the Turtle test above: the arrays of a PLY that the library writes as they are,
    # annotated by the command under the same name, give the same report.
    data = sphere6.read_bytes()
    start = data.index(b"comment")
    (work / "named6.ply").write_bytes(data[:start] + data[data.index(b"\n", start) + 1:])
    done = subprocess.run([command, "annotate", "named6.ply", "--scale", str(SCALE), "-o", "named6.ttl",
                           "--json", "named6.json", "-q"], cwd=work, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    V, F = geotex.read_mesh(str(work / "named6.ply"))
    report = geotex.annotate(V, F, scale=SCALE, name="named6.ply").to_json()
    assert report == (work / "named6.json").read_text()
    assert json.loads(report)["input"]["format"] == "ply-binary-le"
    unnamed = json.loads(geotex.segment(V, F, scale=SCALE).to_json())
    assert unnamed["input"]["file"] == "mesh.ply"
    assert unnamed["texels"] == json.loads(report)["texels"]


def test_a_missing_dictionary_is_the_command_s_message(command, sphere6, work):
    missing = str(work / "missing.yaml")
    code, _, err = run(command, "annotate", sphere6, "--scale", SCALE, "--dictionary", missing,
                       "-o", work / "never.ttl")
    assert code == 2
    seg = geotex.segment(*geotex.read_mesh(str(sphere6)), scale=SCALE)
    with pytest.raises(geotex.IoError) as raised:
        geotex.annotate(seg, dictionary=missing)
    assert err.strip() == "geotex: error: " + str(raised.value)
    with pytest.raises(geotex.IoError, match="it is a directory"):
        geotex.annotate(seg, dictionary=str(work))


def test_scale_auto_and_levels_give_the_command_s_outputs(command, sphere6, work):
    # As `geotex annotate --scale auto --levels`: the same choice, levels, Turtle and report.
    ttl, report = work / "auto6.ttl", work / "auto6.json"
    code, _, err = run(command, "annotate", sphere6, "--scale", "auto", "--levels", "-o", ttl,
                       "--json", report, "-q")
    assert code == 0, err
    a = geotex.annotate_file(str(sphere6), scale="auto", levels=True)
    assert a.to_turtle() == ttl.read_text()
    assert a.to_json() == report.read_text()
    seg, r = a.segmentation, json.loads(report.read_text())
    assert seg.scale == r["parameters"]["scale"] == seg.scale_choice["chosen"]
    assert seg.scale_choice == r["scale_choice"]
    assert [level["scale"] for level in seg.levels] == [level["scale"] for level in r["levels"]]
    for level, expected in zip(seg.levels, r["levels"]):
        assert level["num_texels"] == expected["texel_count"]
        assert level["part_of"].tolist() == [-1 if c is None else c for c in expected["part_of"]]
    main = [level for level in seg.levels if level["main"]]
    assert len(main) == 1 and (main[0]["texel_of_face"] == seg.texel_of_face).all()
    # Without scale="auto" there is no choice and no level.
    plain = geotex.segment(seg.V, seg.F, scale=SCALE)
    assert plain.scale_choice is None and plain.levels == [] and plain.scale == SCALE
    with pytest.raises(geotex.UsageError, match="levels=True needs scale='auto'"):
        geotex.segment(seg.V, seg.F, scale=SCALE, levels=True)
    with pytest.raises(geotex.UsageError, match="'auto'"):
        geotex.segment(seg.V, seg.F, scale="automatic")
    with pytest.raises(geotex.UsageError, match="exactly one of scale"):
        geotex.segment(seg.V, seg.F, scale="auto", radius=0.1)
