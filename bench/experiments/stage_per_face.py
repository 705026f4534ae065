#!/usr/bin/env python3
"""Each stage's cost per face on real meshes against sphere-1 level 7 (issue 21, item 2: no
stage may cost more per face on the CGAL demo meshes than 3x its cost per face on sphere-1
level 7 at the same scale).

  bench/experiments/stage_per_face.py --geotex build/geotex [--runs 3] [--work DIR]

Runs `geotex segment MESH --scale S` for S in 2%, 4% and 8% on sphere-1 level 7
(`geotex synth --level 7`) and on the meshes of Debian's libcgal-demo, --runs times each,
and prints a Markdown table per stage: the median seconds and, per face and per run of the
stage, the ratio to sphere-1's (a stage runs up to three times where rims are possible: the
positive side, the negative one of the rim check, the second smoothing's). A run under
--floor seconds is marked, as its time is mostly fixed cost (thread start, a workspace per
thread) that no mesh size explains. The
clustering works on texels, not faces, so it is shown per texel instead. Only the Python
standard library is used; numbers are printed, never judged.
"""

import argparse
import os
import re
import statistics
import subprocess
import sys
import tarfile
import tempfile

from bench_common import STAGE_LINE

CGAL_DATA = "/usr/share/doc/libcgal-dev/data.tar.gz"  # package libcgal-demo
MESHES = ["fandisk.off", "dino.off", "ChineseDragon-10kv.off", "bunny00.off",
          "refined_elephant.off"]
SCALES = [0.02, 0.04, 0.08]
# Stages whose work is on the texels' faces (growing them, their curvature, their features):
# shown per face in texels as well, since a real scan has far more of them than sphere-1.
IN_TEXELS = {"texels", "curvature", "features"}
SUMMARY = re.compile(r"(\d+) texels? in (\d+) textures?")
TEXTURE_FACES = re.compile(r"^\s*texture \d+ .*: \d+ texels?, (\d+) faces")


def stage_name(line_name):
    """Folds the orientation and pass out of a stage's name: 'depth map (positive)' ->
    'depth map'."""
    return re.sub(r"\s*\(.*\)$", "", line_name)


def run_once(geotex, mesh, scale, work):
    out = os.path.join(work, "out.ply")
    p = subprocess.run([geotex, "segment", mesh, "--scale", str(scale), "-o", out],
                       capture_output=True, text=True, check=True)
    stages = {}  # in the order geotex ran them
    texels = texel_faces = 0
    for line in (p.stderr + p.stdout).splitlines():
        m = STAGE_LINE.match(line)
        if m:
            name = stage_name(m.group(1))
            seconds, passes = stages.get(name, (0.0, 0))
            stages[name] = (seconds + float(m.group(2)), passes + 1)
        m = SUMMARY.search(line)
        if m:
            texels = int(m.group(1))
        m = TEXTURE_FACES.match(line)
        if m:
            texel_faces += int(m.group(1))
    return stages, texels, texel_faces


def num_faces(path):
    """Faces of an OFF or PLY file, from its header."""
    with open(path, "rb") as f:
        head = f.read(4096).decode("latin-1")
    if head.startswith("ply"):
        return int(re.search(r"element face (\d+)", head).group(1))
    tokens = [t for line in head.splitlines() if not line.strip().startswith("#")
              for t in line.split()]
    if tokens[0].endswith("OFF"):  # OFF, COFF, NOFF...: vertex and face counts follow
        return int(tokens[2])
    return int(tokens[1])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--geotex", default="build/geotex")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--floor", type=float, default=0.01,
                    help="stages shorter than this (seconds) are marked as fixed cost")
    ap.add_argument("--work", help="working directory (default: a temporary one)")
    args = ap.parse_args()
    if not os.path.exists(CGAL_DATA):
        sys.exit(f"stage_per_face: {CGAL_DATA} is missing (Debian package libcgal-demo)")
    work = args.work or tempfile.mkdtemp(prefix="geotex-per-face-")
    os.makedirs(work, exist_ok=True)
    sphere = os.path.join(work, "sphere-1-level7.ply")
    if not os.path.exists(sphere):
        subprocess.run([args.geotex, "synth", "--level", "7", "-o", sphere, "--quiet"],
                       check=True)
    with tarfile.open(CGAL_DATA) as tar:
        for name in MESHES:
            member = next(m for m in tar.getmembers() if m.name.endswith("/" + name))
            target = os.path.join(work, name)
            if not os.path.exists(target):
                with tar.extractfile(member) as src, open(target, "wb") as dst:
                    dst.write(src.read())
    meshes = [("sphere-1 level 7", sphere)] + [(n, os.path.join(work, n)) for n in MESHES]
    medians = {}  # (mesh, scale) -> (stage -> seconds, texels, faces in texels)
    order = {}  # stage -> first appearance
    for label, path in meshes:
        for scale in SCALES:
            runs = [run_once(args.geotex, path, scale, work) for _ in range(args.runs)]
            for st, _, _ in runs:
                for s in st:
                    order.setdefault(s, len(order))
            medians[(label, scale)] = (
                {s: (statistics.median(st.get(s, (0.0, 0))[0] for st, _, _ in runs),
                     runs[0][0].get(s, (0.0, 0))[1]) for s in order},
                runs[0][1], runs[0][2])
            print(f"stage_per_face: {label} at {scale}", file=sys.stderr, flush=True)
    faces = {label: num_faces(path) for label, path in meshes}
    stages = sorted(order, key=order.get)
    print(f"Command: `bench/experiments/stage_per_face.py --runs {args.runs}`; median seconds "
          f"(\"in 3\": the stage ran 3 times, e.g. the depth maps of the rim check and of the "
          f"second smoothing), and per face and per run of the stage (per texel for the "
          f"clustering) / sphere-1 level 7's at the same scale; '~' marks a run under "
          f"{args.floor} s. The last table gives the share of the faces that lie in texels.\n")
    for stage in stages:
        per_texel = stage == "clustering"
        print(f"**{stage}**" + (" (per texel)" if per_texel else "") + "\n")
        print("| mesh | faces | " + " | ".join(f"{s:.0%}" for s in SCALES) + " |")
        print("|---|---|" + "---|" * len(SCALES))
        for label, _ in meshes:
            cells = []
            for scale in SCALES:
                st, texels, texel_faces = medians[(label, scale)]
                ref, ref_texels, ref_texel_faces = medians[("sphere-1 level 7", scale)]
                (t, passes) = st.get(stage, (0.0, 0))
                (t_ref, ref_passes) = ref.get(stage, (0.0, 0))
                if per_texel:
                    size, ref_size = texels, ref_texels
                else:
                    size, ref_size = faces[label], faces["sphere-1 level 7"]
                shown = f"{t:.3f}" + (f" in {passes}" if passes > 1 else "")
                if t_ref <= 0 or size <= 0 or passes == 0:
                    cells.append(shown)
                    continue
                ratio = (t / passes / size) / (t_ref / ref_passes / ref_size)
                mark = "~" if t / passes < args.floor else ""
                cell = f"{shown} ({ratio:.1f}x{mark}"
                if stage in IN_TEXELS and texel_faces > 0 and ref_texel_faces > 0:
                    # The same per face in texels, the work these stages do.
                    in_texels = (t / passes / texel_faces) / (t_ref / ref_passes / ref_texel_faces)
                    cell += f"; {in_texels:.1f}x per face in texels"
                cells.append(cell + ")")
            print(f"| {label} | {faces[label]:,} | " + " | ".join(cells) + " |")
        print()
    print("**faces in texels**\n")
    print("| mesh | faces | " + " | ".join(f"{s:.0%}" for s in SCALES) + " |")
    print("|---|---|" + "---|" * len(SCALES))
    for label, _ in meshes:
        shares = [medians[(label, s)][2] / faces[label] for s in SCALES]
        print(f"| {label} | {faces[label]:,} | " + " | ".join(f"{x:.0%}" for x in shares) + " |")


if __name__ == "__main__":
    main()
