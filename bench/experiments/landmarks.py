#!/usr/bin/env python3
"""The clustering with landmarks against the clustering of every texel (issue 21: the clustering
costs the cube of the texels; `--cluster-landmarks`, geometry/clustering.cpp "Landmarks").

  bench/experiments/landmarks.py --build build [--copies 1,10,25,60] [--work DIR]

Segments sphere-1 level 7 at 4% (88 texels of four kinds, four textures), then makes feature
tables of many texels from it: each texel's 18 features repeated --copies times, every copy
moved by Gaussian noise of --jitter times the feature's spread over the texels of its texture
(seeded, so the tables are the same on every run), so that a texture becomes a cloud of many
texels. The truth of a row is the texture of its texel. Each table is clustered by
`geotex_recluster` with every row (--max-points 0) and with each number of landmarks below the
rows; printed per run: textures found, seconds and peak memory of the process, and the
adjusted Rand index against the truth and against the clustering of every row. Only the Python
standard library is used; numbers are printed, never judged.
"""

import argparse
import json
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time

from bench_common import adjusted_rand, git_commit, run_checked, synth_command


def recluster(tool, table, max_points):
    """Labels, seconds and peak RSS (MB) of one geotex_recluster process."""
    t0 = time.time()
    res = subprocess.run(["/usr/bin/time", "-f", "%M", tool, "--max-points", str(max_points), table],
                         capture_output=True, text=True)
    secs = time.time() - t0
    if res.returncode != 0:
        sys.exit("geotex_recluster failed: " + res.stderr)
    peak_kb = int(res.stderr.strip().splitlines()[-1])
    return [int(v) for v in res.stdout.split()], secs, peak_kb / 1024


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--copies", default="1,10,25,60")
    ap.add_argument("--landmarks", default="2000,1000,500")
    ap.add_argument("--jitter", type=float, default=0.5)
    ap.add_argument("--work")
    args = ap.parse_args()
    geotex = os.path.join(args.build, "geotex")
    tool = os.path.join(args.build, "geotex_recluster")
    work = args.work or tempfile.mkdtemp(prefix="geotex-landmarks-")
    os.makedirs(work, exist_ok=True)
    mesh, report = os.path.join(work, "s7.ply"), os.path.join(work, "s7.json")
    run_checked(synth_command(geotex, mesh, os.path.join(work, "s7.truth.json"), 7))
    run_checked([geotex, "segment", mesh, "--scale", "0.04", "-o", os.path.join(work, "s7.seg.ply"),
                 "--json", report, "--quiet"])
    with open(report) as f:
        r = json.load(f)
    # The paper's 18, which the clustering uses: not the sizes relative to the object.
    names = [k for k in r["features"] if not k.endswith("_rel")]
    texels = [[t["features"][k] for k in names] for t in r["texels"]]
    textures = [t["texture"] for t in r["texels"]]
    # Each texture's own spread per feature: copies within it blur its texels into one cloud.
    spread = {}
    for g in set(textures):
        members = [x for x, t in zip(texels, textures) if t == g]
        spread[g] = [statistics.pstdev(col) for col in zip(*members)]

    print(f"Made by `bench/experiments/landmarks.py` on {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}; "
          f"geotex at commit {git_commit(os.path.dirname(os.path.abspath(__file__)))}; sphere-1 level 7 at 4%: "
          f"{len(texels)} texels in {len(set(textures))} textures; each copy moved by {args.jitter} of its texture's "
          f"spread in each feature.\n")
    print("| rows | landmarks | textures | s | peak MB | ARI vs truth | ARI vs every row |")
    print("|---|---|---|---|---|---|---|")
    for copies in [int(c) for c in args.copies.split(",")]:
        rng = random.Random(copies)
        rows, truth = [], []
        for _ in range(copies):
            for t, texel in enumerate(texels):
                rows.append([v + args.jitter * s * rng.gauss(0, 1)
                             for v, s in zip(texel, spread[textures[t]])])
                truth.append(textures[t])
        table = os.path.join(work, f"copies{copies}.tsv")
        with open(table, "w") as f:
            f.write("\t".join(names) + "\n")
            for row in rows:
                f.write("\t".join(repr(v) for v in row) + "\n")
        every, secs, peak = recluster(tool, table, 0)
        print(f"| {len(rows)} | all | {len(set(every))} | {secs:.2f} | {peak:.0f} | "
              f"{adjusted_rand(every, truth):.3f} | 1 |", flush=True)
        for m in [int(v) for v in args.landmarks.split(",")]:
            if m >= len(rows):
                continue
            labels, secs, peak = recluster(tool, table, m)
            print(f"| {len(rows)} | {m} | {len(set(labels))} | {secs:.2f} | {peak:.0f} | "
                  f"{adjusted_rand(labels, truth):.3f} | {adjusted_rand(labels, every):.3f} |",
                  flush=True)


if __name__ == "__main__":
    main()
