#!/usr/bin/env python3
"""Where a scale series spends its time (issue 20, item 4): every stage of every scale.

  bench/experiments/series_stages.py MESH --geotex build/geotex [--threads 1]
                                     [--from 0.01] [--to 0.16] [--steps 12] [--orientation O]

`geotex scales` segments MESH at each scale of its series, each scale bit for bit what
`geotex segment --scale s` computes. This runs `geotex segment MESH --scale s` at each scale of
the default series (12 scales, geometric from 1% to 16% of the largest side; --from, --to and
--steps change it as they change `geotex scales`), skipping those `geotex scales` skips (below
3 mean edge lengths: this script reads them from `geotex scales --json`), and prints the
stage times geotex reports for each scale, then their totals, as a Markdown table. The
stages shared by the whole series (reading, repair, topology) and writing are left out.
Only the Python standard library is used; numbers are printed, never judged.
"""

import argparse
import collections
import json
import os
import subprocess
import sys
import tempfile

from bench_common import STAGE_LINE

SHARED = {"reading", "repair", "topology", "writing"}


def stage_times(stderr):
    """The stages geotex printed ('geotex: NAME   0.123 s'), in order."""
    times = collections.OrderedDict()
    for line in stderr.splitlines():
        m = STAGE_LINE.match(line)
        if m and m.group(1) not in SHARED:
            times[m.group(1)] = times.get(m.group(1), 0.0) + float(m.group(2))
    return times


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("--geotex", default="build/geotex")
    ap.add_argument("--threads", type=int, default=1, help="geotex -j (default 1)")
    ap.add_argument("--from", dest="low", default="0.01")
    ap.add_argument("--to", dest="high", default="0.16")
    ap.add_argument("--steps", default="12")
    ap.add_argument("--orientation", default="positive")
    args = ap.parse_args()

    with tempfile.TemporaryDirectory() as work:
        series_json = os.path.join(work, "series.json")
        subprocess.run([args.geotex, "scales", args.mesh, "--quiet", "--json", series_json,
                        "--from", args.low, "--to", args.high, "--steps", args.steps,
                        "--orientation", args.orientation],
                       check=True, stdout=subprocess.DEVNULL)
        with open(series_json) as f:
            steps = json.load(f)["scales"]
        rows, stages = [], []
        for step in steps:
            if step.get("skipped"):
                continue
            run = subprocess.run(
                [args.geotex, "segment", args.mesh, "--scale", repr(step["scale"]),
                 "--orientation", args.orientation,
                 "-j", str(args.threads), "-o", os.path.join(work, "out.ply")],
                capture_output=True, text=True, check=True)
            times = stage_times(run.stderr)
            for name in times:
                if name not in stages:
                    stages.append(name)
            rows.append((step["scale"], times))

    print("| scale | " + " | ".join(stages) + " | the scale |")
    print("|---" * (len(stages) + 2) + "|")
    totals = collections.defaultdict(float)
    for scale, times in rows:
        cells = [f"{times[s]:.3f}" if s in times else "" for s in stages]
        for s, t in times.items():
            totals[s] += t
        print(f"| {100 * scale:.3g}% | " + " | ".join(cells) + f" | {sum(times.values()):.3f} |")
    whole = sum(totals.values())
    print("| all | " + " | ".join(f"{totals[s]:.2f} ({100 * totals[s] / whole:.0f}%)"
                                   for s in stages) + f" | {whole:.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
