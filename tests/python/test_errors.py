"""geotex.segment's refusals: the classes of geotex.Error, with one-line messages."""

import numpy as np
import pytest

import geotex
from conftest import run

V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)


def refused(cls, *args, **kwargs):
    with pytest.raises(cls) as info:
        geotex.segment(*args, **kwargs)
    message = str(info.value)
    assert message and "\n" not in message
    return message


@pytest.mark.parametrize(
    "keywords, words",
    [
        ({}, "exactly one of scale"),
        ({"scale": 0.1, "radius": 0.1}, "exactly one of scale"),
        ({"scale": 1.5}, "scale must be in (0, 1)"),
        ({"scale": float("nan")}, "scale must be in (0, 1)"),
        ({"radius": -1.0}, "radius must be positive"),
        ({"radius": float("inf")}, "radius must be positive"),
        ({"scale": 0.1, "orientation": "up"}, "orientation must be one of positive, negative, both"),
        ({"scale": 0.1, "smoothing": "gauss"}, "smoothing must be one of twicing, mean"),
        ({"scale": 0.1, "disc": "huge"}, "disc must be one of auto, exact, fast"),
        ({"scale": 0.1, "curvature_scale": 2.0}, "curvature_scale must be in [0.0, 1.0]"),
        ({"scale": 0.1, "merge_overlap": -0.1}, "merge_overlap must be in"),
        ({"scale": 0.1, "min_depth": 1.5}, "min_depth must be in"),
        ({"scale": 0.1, "min_faces": 0}, "min_faces must be in"),
        ({"scale": 0.1, "max_textures": 101}, "max_textures must be in"),
        ({"scale": 0.1, "cluster_landmarks": 1}, "cluster_landmarks must be 0"),
        ({"scale": 0.1, "cluster_landmarks": -1}, "cluster_landmarks must be in"),
        ({"scale": 0.1, "threads": -1}, "threads must be 0"),
    ],
)
def test_keywords_the_command_refuses_are_usage_errors(keywords, words):
    message = refused(geotex.UsageError, V, F, **keywords)
    assert words in message
    assert issubclass(geotex.UsageError, ValueError) and issubclass(geotex.UsageError, geotex.Error)


def test_the_command_refuses_the_same_options(command, tmp_path):
    mesh = tmp_path / "tetra.obj"
    mesh.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    for options in (["--scale", 1.5], ["--orientation", "up"], ["--min-faces", 0], ["--scale", 0.1, "--radius", 1]):
        code, _, _ = run(command, "segment", mesh, *options, "-q", "-o", tmp_path / "out.ply")
        assert code == 1, options


@pytest.mark.parametrize(
    "V2, F2, words",
    [
        (V[:, :2], F, "V must be a #V by 3 array (got shape (4, 2))"),
        (V.ravel(), F, "V must be a #V by 3 array (got shape (12,))"),
        (V, F.T[:2], "F must be a #F by 3 array (got shape (2, 4))"),
        (V.astype(str), F, "V must hold real numbers (got dtype <U32)"),
        (V, F.astype(float), "F must hold integer vertex indices (got dtype float64)"),
        (np.where(np.arange(12).reshape(4, 3) == 4, np.nan, V), F, "V[1, 1] is not finite (nan)"),
        (np.where(np.arange(12).reshape(4, 3) == 0, np.inf, V), F, "V[0, 0] is not finite (inf)"),
        (V, np.where(F == 3, 4, F), "F[1, 2] = 4 is not a row of V (0 to 3)"),
        (V, np.where(F == 3, -1, F), "F[1, 2] = -1 is not a row of V (0 to 3)"),
        (V, np.array([[0, 1, 1]]), "no non-degenerate face"),
        (np.zeros((4, 3)), F, "the bounding box has zero size"),
        ([[0, 0, 0], [1, 0]], F, "V is not an array of coordinates"),
    ],
)
def test_bad_arrays_are_input_errors_with_one_line(V2, F2, words):
    message = refused(geotex.InputError, V2, F2, scale=0.1)
    assert words in message, message


def test_error_classes_form_the_documented_tree():
    assert issubclass(geotex.ParseError, geotex.InputError)
    assert issubclass(geotex.IoError, geotex.InputError) and issubclass(geotex.IoError, OSError)
    assert issubclass(geotex.NumericalError, geotex.ProcessingError)
    for cls in (geotex.UsageError, geotex.InputError, geotex.ProcessingError):
        assert issubclass(cls, geotex.Error) and issubclass(cls, Exception)
    e = geotex.InputError("x")
    assert e.file is None and e.line == 0 and e.column == 0
