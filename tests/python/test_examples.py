"""The Python examples run: the notebook's code cells in order, and the Open3D example where
Open3D is installed (a large package, not a test dependency)."""

import importlib.util
import json
import os
import shutil
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

EXAMPLES = SOURCE_DIR / "examples" / "python"


def test_notebook_runs_and_each_texture_holds_one_kind(command, tmp_path, monkeypatch, capsys):
    notebook = json.loads((EXAMPLES / "segmentation.ipynb").read_text())
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("GEOTEX_COMMAND", command)
    scope = {}
    for cell in notebook["cells"]:
        if cell["cell_type"] == "code":
            exec(compile("".join(cell["source"]), "segmentation.ipynb", "exec"), scope)
    out = capsys.readouterr().out
    # Sphere-1 at level 6 and 4%: four textures, one per shape kind (the command's answer).
    assert scope["seg"].num_textures == 4
    kinds = [line for line in out.splitlines() if line.startswith("texture ") and "{" in line]
    assert len(kinds) == 4 and all(line.count(":") == 2 for line in kinds), kinds


@pytest.mark.skipif(importlib.util.find_spec("open3d") is None, reason="open3d is not installed")
def test_open3d_example_draws_the_textures(sphere6, tmp_path):
    png = tmp_path / "picture.png"
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    # Under Xvfb where it is installed (a PNG then), else without a display (Debian's Open3D
    # renders nothing headless: the coloured mesh as PLY then).
    xvfb = ["xvfb-run", "-a", "-s", "-screen 0 1024x768x24"] if shutil.which("xvfb-run") else []
    done = subprocess.run(
        [*xvfb, sys.executable, str(EXAMPLES / "open3d_segmentation.py"), str(sphere6),
         "--screenshot", str(png)],
        capture_output=True, text=True, env=env, timeout=120,
    )
    assert done.returncode == 0, done.stderr
    assert "88 texels in 4 textures" in done.stdout
    written = png if xvfb else tmp_path / "picture.ply"
    assert written.exists() and written.stat().st_size > 10000, done.stdout
    if xvfb:
        assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
