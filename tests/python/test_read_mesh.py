"""geotex.read_mesh against hand-written files whose arrays are known."""

import numpy as np
import pytest

import geotex
from conftest import run

# A tetrahedron, consistently oriented outward (counter-clockwise seen from outside).
TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
TETRA_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def write_obj(path, V, F):
    lines = [f"v {x} {y} {z}" for x, y, z in V] + [
        "f " + " ".join(str(i + 1) for i in face) for face in F
    ]
    path.write_text("\n".join(lines) + "\n")


def test_obj_gives_its_arrays(tmp_path):
    path = tmp_path / "tetra.obj"
    write_obj(path, TETRA_V, TETRA_F)
    V, F = geotex.read_mesh(str(path))
    assert V.dtype == np.float64 and V.shape == (4, 3)
    assert F.dtype in (np.int32, np.int64) and F.shape == (4, 3)
    np.testing.assert_array_equal(V, TETRA_V)
    np.testing.assert_array_equal(F, TETRA_F)


def test_ascii_ply_quad_is_triangulated_and_duplicates_merged(tmp_path):
    # A unit square as one quad, plus a triangle on its edge 1-2 whose vertices repeat
    # vertices 1 and 2: the quad becomes two triangles, the repeats merge into 1 and 2.
    path = tmp_path / "quad.ply"
    path.write_text(
        "ply\nformat ascii 1.0\nelement vertex 7\nproperty float x\nproperty float y\n"
        "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n1 0 0\n1 1 0\n2 0.5 0\n"
        "4 0 1 2 3\n3 4 6 5\n"
    )
    V, F = geotex.read_mesh(str(path))
    # Vertices keep their first-occurrence order, the repeats (rows 4, 5) merged away.
    np.testing.assert_array_equal(V, [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0.5, 0]])
    assert F.shape == (3, 3)
    quad = set(map(tuple, np.sort(F[:2], axis=1)))
    assert quad in ({(0, 1, 2), (0, 2, 3)}, {(0, 1, 3), (1, 2, 3)})
    assert sorted(F[2]) == [1, 2, 4]


def test_arrays_are_read_only_views_that_keep_the_mesh_alive(tmp_path):
    path = tmp_path / "tetra.obj"
    write_obj(path, TETRA_V, TETRA_F)
    V, F = geotex.read_mesh(str(path))
    assert not V.flags.writeable and not F.flags.writeable
    with pytest.raises(ValueError):
        V[0, 0] = 1
    del F
    np.testing.assert_array_equal(V.copy(), TETRA_V)


def test_missing_file_is_an_io_error_naming_it(tmp_path):
    path = tmp_path / "missing.ply"
    with pytest.raises(geotex.IoError) as info:
        geotex.read_mesh(str(path))
    assert isinstance(info.value, OSError) and isinstance(info.value, geotex.InputError)
    assert str(path) in str(info.value) and info.value.file == str(path)


def test_malformed_ply_is_a_parse_error_with_the_place_as_the_command_says(command, tmp_path):
    path = tmp_path / "bad.ply"
    path.write_text(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 zero 0\n0 1 0\n3 0 1 2\n"
    )
    with pytest.raises(geotex.ParseError) as info:
        geotex.read_mesh(str(path))
    assert info.value.file == str(path) and info.value.line == 11 and info.value.column == 3
    code, _, err = run(command, "segment", path, "--scale", 0.1, "-q", "-o", tmp_path / "out.ply")
    assert code == 2
    assert err.strip() == "geotex: error: " + str(info.value)


def test_unknown_extension_and_no_face_left_are_input_errors(command, tmp_path):
    with pytest.raises(geotex.InputError) as info:
        geotex.read_mesh(str(tmp_path / "mesh.xyz"))
    assert "mesh.xyz" in str(info.value)
    degenerate = tmp_path / "flat.obj"
    write_obj(degenerate, [[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1, 2]])
    with pytest.raises(geotex.InputError) as info:
        geotex.read_mesh(str(degenerate))
    code, _, err = run(command, "segment", degenerate, "--scale", 0.1, "-q", "-o", tmp_path / "out.ply")
    assert code == 2 and err.strip() == "geotex: error: " + str(info.value)
