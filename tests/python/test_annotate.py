"""geotex.annotate and geotex.annotate_file against `geotex annotate`: the same bytes of
Turtle, N-Triples and JSON-LD, the same words as the JSON report, and the command's refusals."""

import json

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
