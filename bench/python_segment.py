#!/usr/bin/python3
"""Python costs nothing (issue 18): geotex.segment against `geotex segment` on sphere-1.

    /usr/bin/python3 bench/python_segment.py [--build build] [--level 7] [--scale 0.04] [--runs 7]

Makes sphere-1 (`geotex synth --level L`), then alternates RUNS runs of
  - the command, `geotex segment MESH --scale S -o OUT.ply`, timed from outside (wall) and by its
    own stage times on stderr: the same work as geotex.segment is its repair and pipeline
    stages (everything but reading the file and writing the PLY);
  - a fresh interpreter that imports geotex, reads the mesh and segments it, timed from
    outside (wall, beside the command's) and around its geotex.segment call (the one copy of
    the arrays, the repair, the pipeline, the result object): the same work, in a process
    as new as the command's;
  - geotex.segment in this process, called again and again (warm: the thread pool running,
    the allocator's memory reused), for information.
Prints the medians and the ratios as a Markdown table; checks that both find the same texels.
Needs the module built (PYTHONPATH=BUILD/python is set here) for /usr/bin/python3.
"""

import argparse
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

STAGE = re.compile(r"^geotex: (.+?)\s+([0-9.]+) s$")


def command_run(geotex, mesh, scale, out):
    start = time.perf_counter()
    done = subprocess.run([geotex, "segment", mesh, "--scale", str(scale), "-o", out],
                          capture_output=True, text=True, check=True)
    wall = time.perf_counter() - start
    stages = {}
    for line in done.stderr.splitlines():
        m = STAGE.match(line)
        if m:
            stages[m.group(1)] = float(m.group(2))
    work = sum(t for name, t in stages.items() if name not in ("reading", "writing"))
    texels = int(re.search(r": (\d+) texels in", done.stdout).group(1))
    return wall, work, texels


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--level", type=int, default=7)
    ap.add_argument("--scale", type=float, default=0.04)
    ap.add_argument("--runs", type=int, default=7)
    a = ap.parse_args()
    build = Path(a.build).resolve()
    geotex_cmd = str(build / "geotex")
    sys.path.insert(0, str(build / "python"))
    import geotex

    with tempfile.TemporaryDirectory() as tmp:
        mesh = str(Path(tmp) / f"sphere1-{a.level}.ply")
        subprocess.run([geotex_cmd, "synth", "--level", str(a.level), "-o", mesh, "--quiet"],
                       check=True, stdout=subprocess.DEVNULL)
        out = str(Path(tmp) / "seg.ply")
        script = ("import sys, time; sys.path.insert(0, %r); import geotex; "
                  "V, F = geotex.read_mesh(%r); t = time.perf_counter(); "
                  "geotex.segment(V, F, scale=%r); print(time.perf_counter() - t)"
                  % (str(build / "python"), mesh, a.scale))
        V, F = geotex.read_mesh(mesh)
        cmd_wall, cmd_work, py_call, py_wall, py_fresh = [], [], [], [], []
        for _ in range(a.runs):
            wall, work, texels = command_run(geotex_cmd, mesh, a.scale, out)
            cmd_wall.append(wall)
            cmd_work.append(work)
            start = time.perf_counter()
            seg = geotex.segment(V, F, scale=a.scale)
            py_call.append(time.perf_counter() - start)
            assert seg.num_texels == texels, (seg.num_texels, texels)
            del seg
            start = time.perf_counter()
            done = subprocess.run([sys.executable, "-c", script], check=True,
                                  capture_output=True, text=True)
            py_wall.append(time.perf_counter() - start)
            py_fresh.append(float(done.stdout))

    med = statistics.median
    print(f"sphere-1 level {a.level} ({len(F):,} faces), scale {a.scale}, {texels} texels, "
          f"median of {a.runs} alternating runs, seconds")
    print()
    print("| measure | geotex segment | Python | ratio |")
    print("|---|---|---|---|")
    print(f"| the same work (command: repair and pipeline stages; Python: the geotex.segment call "
          f"in a fresh interpreter) | {med(cmd_work):.3f} | {med(py_fresh):.3f} | "
          f"{med(py_fresh) / med(cmd_work):.3f} |")
    print(f"| the same, Python warm (geotex.segment called again in one process) "
          f"| {med(cmd_work):.3f} | {med(py_call):.3f} | {med(py_call) / med(cmd_work):.3f} |")
    print(f"| whole process (command: read, segment, write the PLY; Python: start, import, "
          f"read_mesh, segment) | {med(cmd_wall):.3f} | {med(py_wall):.3f} | "
          f"{med(py_wall) / med(cmd_wall):.3f} |")
    print()
    print("runs: command work " + " ".join(f"{t:.3f}" for t in cmd_work) +
          "; segment call, fresh " + " ".join(f"{t:.3f}" for t in py_fresh) +
          "; warm " + " ".join(f"{t:.3f}" for t in py_call))


if __name__ == "__main__":
    main()
