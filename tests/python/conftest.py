"""Fixtures of the Python module's tests: the geotex command of the same build (ctest passes
GEOTEX_COMMAND), and meshes with the command's own outputs to compare with."""

import json
import os
import subprocess
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
SOURCE_DIR = Path(os.environ.get("GEOTEX_SOURCE_DIR", HERE.parent.parent))


@pytest.fixture(scope="session")
def command():
    path = os.environ.get("GEOTEX_COMMAND")
    if not path:
        pytest.skip("GEOTEX_COMMAND (the geotex command of this build) is not set; run through ctest")
    return os.path.abspath(path)


def run(command, *args):
    """Runs the command; returns (exit code, stdout, stderr)."""
    done = subprocess.run([command, *map(str, args)], capture_output=True, text=True)
    return done.returncode, done.stdout, done.stderr


def read_segmentation_ply(path):
    """Per-face texel and texture of an ASCII segmentation PLY, read here without geotex."""
    with open(path) as f:
        lines = f.read().splitlines()
    end = lines.index("end_header")
    header = lines[:end]
    counts = {l.split()[1]: int(l.split()[2]) for l in header if l.startswith("element ")}
    face_props = header[header.index(next(l for l in header if l.startswith("element face"))) + 1:]
    names = [l.split()[-1] for l in face_props if l.startswith("property")]
    assert names[:3] == ["vertex_indices", "texel", "texture"], names
    faces = lines[end + 1 + counts["vertex"]:end + 1 + counts["vertex"] + counts["face"]]
    texel, texture = [], []
    for line in faces:
        fields = line.split()
        n = int(fields[0])
        texel.append(int(fields[1 + n]))
        texture.append(int(fields[2 + n]))
    return texel, texture


class CommandRun:
    """A mesh segmented by the command: its JSON report and per-face labels."""

    def __init__(self, mesh, report, texel_of_face, texture_of_face):
        self.mesh = mesh
        self.report = report
        self.texel_of_face = texel_of_face
        self.texture_of_face = texture_of_face


def segment_with_command(command, mesh, out_dir, name, *options):
    seg, js = out_dir / f"{name}.seg.ply", out_dir / f"{name}.json"
    code, _, err = run(command, "segment", mesh, "-o", seg, "--json", js, "--ascii", "-q", *options)
    assert code == 0, err
    texel, texture = read_segmentation_ply(seg)
    return CommandRun(mesh, json.loads(js.read_text()), texel, texture)


@pytest.fixture(scope="session")
def work(tmp_path_factory):
    return tmp_path_factory.mktemp("geotex-python")


@pytest.fixture(scope="session")
def sphere6(command, work):
    """Sphere-1 at level 6 (81,920 faces, four textures at 4%)."""
    mesh = work / "sphere6.ply"
    code, _, err = run(command, "synth", "--level", 6, "-o", mesh, "-q")
    assert code == 0, err
    return mesh


@pytest.fixture(scope="session")
def engraved5(command, work):
    """Sphere-1 at level 5 with half of the shapes engraved (both orientations)."""
    mesh = work / "engraved5.ply"
    code, _, err = run(command, "synth", "--level", 5, "--engraved", 0.5, "-o", mesh, "-q")
    assert code == 0, err
    return mesh
