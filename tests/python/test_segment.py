"""geotex.segment against the command's own outputs for the same mesh and options: the
segmentation PLY's per-face labels and the JSON report's texels, textures and features."""

import threading
import time

import numpy as np
import pytest

import geotex
from conftest import segment_with_command


def features_of(report):
    """#texels by #features from the report, NaN for null (an undefined feature)."""
    names = report["features"]
    return np.array(
        [[np.nan if t["features"][n] is None else t["features"][n] for n in names] for t in report["texels"]],
        dtype=float,
    ).reshape(len(report["texels"]), len(names))


def assert_same_as_command(seg, run):
    report = run.report
    assert seg.num_texels == len(report["texels"])
    assert seg.num_textures == len(report["textures"])
    np.testing.assert_array_equal(seg.texel_of_face, run.texel_of_face)
    np.testing.assert_array_equal(seg.texture_of_face, run.texture_of_face)
    assert seg.radius == report["parameters"]["radius"]
    assert seg.feature_names == report["features"]
    # The report writes doubles to 17 digits, so the values compare exactly.
    np.testing.assert_array_equal(seg.feature_values, features_of(report))
    for k, name in enumerate(seg.feature_names):
        np.testing.assert_array_equal(seg.features[name], seg.feature_values[:, k])
    for i, texel in enumerate(report["texels"]):
        np.testing.assert_array_equal(seg.texel_faces[i], texel["faces"])
        assert seg.texel_texture[i] == texel["texture"]
        assert seg.texel_orientation[i] == texel["orientation"]
        assert seg.texel_seed[i] == texel["seed_vertex"]
        assert seg.texel_depth_threshold[i] == texel["depth_threshold"]
    for k, texture in enumerate(report["textures"]):
        np.testing.assert_array_equal(seg.texture_texels[k], texture["texels"])
        assert seg.texture_orientation[k] == texture["orientation"]
    assert sorted(seg.vertex_depth) == sorted(d["orientation"] for d in report["depth"])
    for d in report["depth"]:
        assert seg.vertex_depth[d["orientation"]].max() == d["max_depth"]


def test_default_options_match_the_command(command, sphere6, work):
    run = segment_with_command(command, sphere6, work, "sphere6-default", "--scale", 0.04)
    V, F = geotex.read_mesh(str(sphere6))
    seg = geotex.segment(V, F, scale=0.04)
    assert seg.num_textures == 4  # sphere-1's four shape kinds, the command's answer too
    assert_same_as_command(seg, run)
    assert seg.V.shape == V.shape and seg.F.shape == F.shape
    np.testing.assert_array_equal(seg.source_face, np.arange(len(F)))
    assert seg.vertex_depth["positive"].shape == (len(V),)
    assert seg.face_depth["positive"].shape == (len(F),)


def test_every_option_reaches_the_pipeline_as_the_command_s(command, engraved5, work):
    options = dict(
        radius=0.1, orientation="Both", smoothing="mean", disc="exact", curvature_scale=0,
        vertex_mean=True, keep_rims=True, merge_overlap=0.3, min_depth=0.02, min_faces=5,
        max_textures=3, cluster_landmarks=4,
    )
    run = segment_with_command(
        command, engraved5, work, "engraved5-options", "--radius", 0.1, "--orientation", "Both",
        "--smoothing", "mean", "--disc", "exact", "--curvature-scale", 0, "--vertex-mean",
        "--keep-rims", "--merge-overlap", 0.3, "--min-depth", 0.02, "--min-faces", 5,
        "--max-textures", 3, "--cluster-landmarks", 4,
    )
    V, F = geotex.read_mesh(str(engraved5))
    seg = geotex.segment(V, F, **options)
    assert {"positive", "negative"} <= set(seg.texel_orientation)
    assert_same_as_command(seg, run)
    assert seg.orientation == "both"
    # And the options matter: the defaults give another segmentation of this mesh.
    default = geotex.segment(V, F, radius=0.1, orientation="both")
    assert not np.array_equal(default.texel_of_face, seg.texel_of_face)


def test_tiles_give_the_whole_mesh_s_segmentation(engraved5):
    V, F = geotex.read_mesh(str(engraved5))
    whole = geotex.segment(V, F, scale=0.05, orientation="both")
    tiled = geotex.segment(V, F, scale=0.05, orientation="both", tiles=4)
    assert whole.num_texels > 0
    np.testing.assert_array_equal(tiled.texel_of_face, whole.texel_of_face)
    np.testing.assert_array_equal(tiled.texture_of_face, whole.texture_of_face)
    for bad in (-1, 10001):
        with pytest.raises(geotex.UsageError, match="tiles"):
            geotex.segment(V, F, scale=0.05, tiles=bad)
    with pytest.raises(geotex.UsageError, match="tiles with scale='auto'"):
        geotex.segment(V, F, scale="auto", tiles=4)


def test_same_result_with_one_and_two_threads(engraved5):
    V, F = geotex.read_mesh(str(engraved5))
    one = geotex.segment(V, F, scale=0.05, orientation="both", threads=1)
    two = geotex.segment(V, F, scale=0.05, orientation="both", threads=2)
    assert one.num_texels > 0
    np.testing.assert_array_equal(one.texel_of_face, two.texel_of_face)
    np.testing.assert_array_equal(one.texture_of_face, two.texture_of_face)
    np.testing.assert_array_equal(one.feature_values, two.feature_values)
    for o in one.vertex_depth:
        np.testing.assert_array_equal(one.vertex_depth[o], two.vertex_depth[o])


def test_any_layout_and_dtype_of_the_arrays_gives_the_same_result(engraved5):
    V, F = geotex.read_mesh(str(engraved5))
    reference = geotex.segment(V, F, scale=0.05)
    # Fortran order, int64 and uint32 indices, a strided view, plain lists: read as they are.
    wide = np.zeros((len(V), 6))
    wide[:, ::2] = V
    for V2, F2 in [
        (np.asfortranarray(V), F.astype(np.int64)),
        (wide[:, ::2], F.astype(np.uint32)),
        (V.tolist(), F.tolist()),
    ]:
        seg = geotex.segment(V2, F2, scale=0.05)
        np.testing.assert_array_equal(seg.texel_of_face, reference.texel_of_face)
        np.testing.assert_array_equal(seg.feature_values, reference.feature_values)


def test_repaired_input_is_reported_and_mapped_back(engraved5):
    V, F = geotex.read_mesh(str(engraved5))
    # Face 0 again at the end (a duplicate) and a degenerate face in front: both are removed,
    # and source_face maps the result's faces back to the rows of this F.
    F2 = np.vstack([[[0, 0, 1]], F, F[:1]])
    seg = geotex.segment(V, F2, scale=0.05)
    reference = geotex.segment(V, F, scale=0.05)
    assert seg.repair["degenerate_faces_removed"] == 1
    assert seg.repair["duplicate_faces_removed"] == 1
    np.testing.assert_array_equal(seg.source_face, np.arange(1, len(F) + 1))
    np.testing.assert_array_equal(seg.F, F)
    np.testing.assert_array_equal(seg.texel_of_face, reference.texel_of_face)


def test_results_are_read_only_views_that_outlive_the_result(engraved5):
    V, F = geotex.read_mesh(str(engraved5))
    seg = geotex.segment(V, F, scale=0.05)
    labels, area, expected = seg.texture_of_face, seg.features["area"], seg.texture_of_face.copy()
    assert not labels.flags.writeable and not labels.flags.owndata
    with pytest.raises(ValueError):
        labels[0] = 7
    del seg
    np.testing.assert_array_equal(labels, expected)
    assert np.isfinite(area).all()


def test_nothing_salient_warns_and_gives_empty_arrays(engraved5):
    V, F = geotex.read_mesh(str(engraved5))
    with pytest.warns(UserWarning, match="no salient detail"):
        seg = geotex.segment(V, F, scale=0.04, min_depth=1)
    assert seg.num_texels == 0 and seg.feature_values.shape == (0, len(seg.feature_names))
    assert (seg.texel_of_face == -1).all()


def test_the_gil_is_released_during_the_work(sphere6):
    V, F = geotex.read_mesh(str(sphere6))
    ticks = 0
    stop = threading.Event()

    def count():
        nonlocal ticks
        while not stop.is_set():
            ticks += 1
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    try:
        time.sleep(0.05)
        before = ticks
        start = time.perf_counter()
        geotex.segment(V, F, scale=0.04, threads=1)
        elapsed = time.perf_counter() - start
        during = ticks - before
    finally:
        stop.set()
        counter.join()
    # Holding the GIL, the call would let the counter run only at its start and end (and
    # during the repair, which is a tenth of the work at most); released, the counter ticks
    # through it, about once a millisecond (a quarter of that leaves room for a loaded machine).
    assert elapsed > 0.1
    assert during >= 250 * elapsed, (during, elapsed)
