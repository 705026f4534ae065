#!/usr/bin/env python3
"""The scale cases of issue 20 (item 5): hard inscriptions with ground truth, scored at every
fixed scale, and with `--scale auto` when this geotex has it.

    bench/experiments/scale_cases.py [--geotex PATH] [--work DIR] [--cases a,b] [--jobs N]
                                     [--results FILE] [--keep]

For each case the mesh and its ground truth are made into the work directory (the
inscriptions by bench/experiments/inscription.py --case NAME, sphere-1 by `geotex synth
--level 7`), then every scale of a geometric series, r_k = 0.01 * 16^(k/11), k = 0 ... 11
(1% to 16% of the largest bounding-box side), is run as

    geotex segment MESH --scale r --orientation both -o seg.ply --json report.json

and scored by `geotex evaluate seg.ply truth.json` (bench/README.md, *Scoring*: a shape is
matched when exactly one texel covers it, split when several do, missed when none does; a
texel that covers no shape is spurious). When `geotex segment --help` offers `auto` as a
--scale value (the lead's feature of issue 20), `--scale auto` is run too and its row added,
with the scale it chose (from its report) and issue 20's target: at least 95% of the matched
shapes of the best fixed scale, with no more spurious texels.

Cases: short, long, mixed (inscription.py's, see its --list) and sphere-1 (the control, 88
shapes; the target there is 88/88). sphere-1's details are all raised, so it is run with the
paper's `--orientation positive` as well as `both`: two tables.

Prints one Markdown table per case on stdout; --results FILE also replaces the part of FILE
between `<!-- scale-cases:begin -->` and `<!-- scale-cases:end -->` (bench/RESULTS.md).
"""

import argparse
import concurrent.futures
import datetime
import json
import os
import re
import shutil
import subprocess
import sys
import time

from bench_common import git_commit, replace_section, run_checked, source_of, synth_command

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
BEGIN, END = "<!-- scale-cases:begin -->", "<!-- scale-cases:end -->"

# name -> how its mesh is made and which orientations are scored.
CASES = {
    "short": {"inscription": "short", "orientations": ["both"],
              "about": "a short inscription in large, broad letters (\"SPQR\" / \"ROMA\", cap height 0.22 and groove "
                       "width 0.036 on a 1.4 × 0.9 stone) and 8 raised bosses: 16 details"},
    "long": {"inscription": "long", "orientations": ["both"],
             "about": "a long inscription in small letters (\"IMP CAESAR\" / \"DIVI F AVGVSTVS\" / \"COS XI\", cap "
                      "height 0.085, groove width 0.01) and 4 bosses: 31 details"},
    "mixed": {"inscription": "mixed", "orientations": ["both"],
              "about": "both letter sizes on one stone (\"SPQR\" as in short above \"DIVI F AVGVSTVS\" / \"COS XI\" "
                       "as in long) and 4 bosses: 26 details"},
    "sphere-1": {"synth": 7, "orientations": ["positive", "both"],
                 "about": "the paper's sphere-1 (`geotex synth --level 7`): 88 raised shapes of four kinds, the "
                          "control"},
}
DEFAULT_CASES = ["short", "long", "mixed", "sphere-1"]


def scale_series(lo=0.01, hi=0.16, steps=12):
    """r_k = lo * (hi/lo)^(k/(steps-1)): issue 20's default series (1% to 16%, 12 steps)."""
    return [lo * (hi / lo) ** (k / (steps - 1)) for k in range(steps)]


def has_auto_scale(geotex):
    """True when `geotex segment --help` lists `auto` in the --scale option's own text. Other
    options (--disc auto|exact|fast) say auto too, so only the --scale entry is read: its
    first line and the indented lines that continue it."""
    out = subprocess.run([geotex, "segment", "--help"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True).stdout
    lines = out.splitlines()
    for i, line in enumerate(lines):
        if re.match(r"\s*(-s,)?--scale\b", line):
            block = [line]
            for nxt in lines[i + 1:]:
                if re.match(r"\s*-", nxt) or not nxt.strip():
                    break
                block.append(nxt)
            return re.search(r"\bauto\b", " ".join(block)) is not None
    return False


def chosen_scale(report):
    """The scale a run used, as a fraction of the largest side: parameters.scale when it is a
    number, else the radius over the largest side (what `--scale auto` picked, whatever
    the report calls it)."""
    p = report.get("parameters", {})
    if isinstance(p.get("scale"), (int, float)):
        return float(p["scale"])
    side = report.get("mesh", {}).get("largest_side")
    if isinstance(p.get("radius"), (int, float)) and side:
        return p["radius"] / side
    return None


class Runner:
    def __init__(self, args, work):
        self.geotex = args.geotex
        self.work = work
        self.keep = args.keep
        self.threads = args.threads

    def path(self, *parts):
        return os.path.join(self.work, *parts)

    def make_case(self, name):
        """The mesh and truth of a case, made once into the work directory."""
        case = CASES[name]
        mesh, truth = self.path(name + ".ply"), self.path(name + ".truth.json")
        if "inscription" in case:
            run_checked([sys.executable, os.path.join(HERE, "inscription.py"), mesh, truth,
                         "--case", case["inscription"]])
        else:
            run_checked(synth_command(self.geotex, mesh, truth, case["synth"]))
        return mesh, truth

    def score(self, name, mesh, truth, orientation, scale):
        """One `segment` and its `evaluate`; scale is a number or "auto"."""
        tag = "%s-%s-%s" % (name, orientation, scale if scale == "auto" else "%.4f" % scale)
        seg, rep, sc = self.path(tag + ".seg.ply"), self.path(tag + ".report.json"), self.path(tag + ".scores.json")
        value = scale if scale == "auto" else repr(scale)
        _, secs = run_checked([self.geotex, "segment", mesh, "--scale", value, "--orientation", orientation,
                               "-o", seg, "--json", rep, "--quiet", "--threads", str(self.threads)])
        run_checked([self.geotex, "evaluate", seg, truth, "--json", sc, "--quiet", "--threads", str(self.threads)])
        with open(rep) as f:
            report = json.load(f)
        with open(sc) as f:
            s = json.load(f)
        row = {"scale": scale, "r": chosen_scale(report), "radius": report.get("parameters", {}).get("radius"),
               "textures": len(report.get("textures", [])), "seconds": secs}
        for key in ("shapes", "texels", "matched", "split", "missed", "spurious", "ari_kind"):
            row[key] = s[key]
        if scale == "auto":
            # Whatever the lead's report says of the choice (candidates, scores), kept whole.
            row["selection"] = {k: v for k, v in report.get("parameters", {}).items()
                                if k == "scale" or any(w in k for w in ("candidate", "chosen", "selection", "level"))}
        if not self.keep:
            for p in (seg, rep, sc):
                os.remove(p)
        return row


def best_fixed(rows):
    """The best fixed scale: most shapes matched, then fewest spurious texels, then fewest
    split, then the smaller scale (cheaper)."""
    fixed = [r for r in rows if r["scale"] != "auto"]
    return min(fixed, key=lambda r: (-r["matched"], r["spurious"], r["split"], r["scale"]))


def as_good(rows):
    """The fixed scales that score as the best one (same matched, spurious and split): the
    plateau an automatic choice may land anywhere on."""
    best = best_fixed(rows)
    key = (best["matched"], best["spurious"], best["split"])
    return [r["scale"] for r in rows if r["scale"] != "auto" and (r["matched"], r["spurious"], r["split"]) == key]


def summary(results):
    """One row per case and orientation: the best fixed scale, its plateau, and auto's row."""
    L = ["| case | orientation | shapes | best fixed r | matched | spurious | as good | auto |",
         "|---|---|---|---|---|---|---|---|"]
    for res in results:
        rows = res["rows"]
        best = best_fixed(rows)
        auto = next((r for r in rows if r["scale"] == "auto"), None)
        L.append("| %s | %s | %d | %s | %d | %d | %s | %s |" % (
            res["case"], res["orientation"], best["shapes"], pct(best["scale"]), best["matched"], best["spurious"],
            ", ".join(pct(r) for r in as_good(rows)),
            "–" if auto is None else "%s: %d matched, %d spurious" % (
                pct(auto["r"]) if auto["r"] is not None else "?", auto["matched"], auto["spurious"])))
    return L + [""]


def auto_verdict(rows):
    """Issue 20's target for `--scale auto` against the best fixed scale, or None."""
    auto = next((r for r in rows if r["scale"] == "auto"), None)
    if auto is None:
        return None
    best = best_fixed(rows)
    ok = auto["matched"] >= 0.95 * best["matched"] and auto["spurious"] <= best["spurious"]
    return "%s: auto matched %d, spurious %d; best fixed (r = %s) %d, %d" % (
        "meets the target" if ok else "misses the target", auto["matched"], auto["spurious"], pct(best["scale"]),
        best["matched"], best["spurious"])


def pct(r):
    return "%.2f%%" % (100 * r) if r < 0.1 else "%.1f%%" % (100 * r)


def table(name, orientation, rows, faces):
    """The Markdown table of one case and orientation."""
    best = best_fixed(rows)
    L = ["**%s**, `--orientation %s`: %s; %s faces. Best fixed scale: r = %s (%d matched, %d spurious)." % (
        name, orientation, CASES[name]["about"], "{:,}".format(faces), pct(best["scale"]), best["matched"],
        best["spurious"]), "",
         "| r | radius (mesh units) | texels | textures | matched | split | missed | spurious | s |",
         "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["scale"] == "auto":
            label = "auto (chose %s)" % (pct(r["r"]) if r["r"] is not None else "?")
        else:
            label = pct(r["scale"])
        mark = "**" if r is best else ""
        L.append("| %s%s%s | %s | %d | %d | %s%d/%d%s | %d | %d | %s%d%s | %.1f |" % (
            mark, label, mark, "%.4g" % r["radius"] if r["radius"] is not None else "–", r["texels"], r["textures"],
            mark, r["matched"], r["shapes"], mark, r["split"], r["missed"], mark, r["spurious"], mark, r["seconds"]))
    verdict = auto_verdict(rows)
    if verdict:
        L += ["", "`--scale auto` " + verdict + "."]
    L.append("")
    return L


def shown_args(argv):
    """The command line as the results name it: without the options that only say where files
    go (--results, --work, --keep), which do not change a number."""
    out, skip = [], False
    for a in argv:
        if skip:
            skip = False
        elif a in ("--results", "--work"):
            skip = True
        elif not a.startswith(("--results=", "--work=", "--keep")):
            out.append(a)
    return out


def mesh_faces(truth):
    with open(truth) as f:
        return len(json.load(f)["face_shape"])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--geotex", default=os.path.join(ROOT, "build", "geotex"), help="geotex command (default: build/geotex)")
    ap.add_argument("--work", help="work directory (default: out/scale-cases; emptied first)")
    ap.add_argument("--cases", default=",".join(DEFAULT_CASES),
                    help="comma-separated cases among %s (default: all)" % ", ".join(DEFAULT_CASES))
    ap.add_argument("--jobs", type=int, default=1,
                    help="runs at once (default 1); each geotex then gets nproc/N threads, so the times grow")
    ap.add_argument("--scales", help="comma-separated scales instead of the series (fractions, e.g. 0.03,0.06)")
    ap.add_argument("--results", help="also replace the scale-cases section of this file (bench/RESULTS.md)")
    ap.add_argument("--keep", action="store_true", help="keep the segmentations, reports and scores")
    args = ap.parse_args()
    cases = [c for c in args.cases.split(",") if c]
    for c in cases:
        if c not in CASES:
            ap.error("unknown case %r (known: %s)" % (c, ", ".join(DEFAULT_CASES)))
    if args.jobs < 1:
        ap.error("--jobs must be at least 1")
    if args.results and not os.path.isfile(args.results):
        # Checked now rather than after the runs: the section goes into an existing file.
        ap.error("--results %s: no such file" % args.results)
    if not os.access(args.geotex, os.X_OK):
        sys.exit("scale_cases: %s is missing: build it first (ninja -C build geotex)" % args.geotex)
    args.threads = max(1, len(os.sched_getaffinity(0)) // args.jobs)
    scales = [float(x) for x in args.scales.split(",")] if args.scales else scale_series()
    auto = has_auto_scale(args.geotex)
    work = args.work or os.path.join(ROOT, "out", "scale-cases")
    if os.path.isdir(work):
        shutil.rmtree(work)
    os.makedirs(work)
    runner = Runner(args, work)
    started = time.time()
    results = []
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for name in cases:
            mesh, truth = runner.make_case(name)
            faces = mesh_faces(truth)
            for orientation in CASES[name]["orientations"]:
                values = scales + (["auto"] if auto else [])
                # map keeps the order of the series whatever order the runs end in.
                rows = list(pool.map(lambda s: runner.score(name, mesh, truth, orientation, s), values))
                for r in rows:
                    print("[scales] %-8s %-8s %-16s texels %3d  matched %3d/%d  split %2d  missed %2d  spurious %3d  "
                          "(%.1f s)" % (name, orientation, pct(r["scale"]) if r["scale"] != "auto" else
                                        "auto (%s)" % (pct(r["r"]) if r["r"] else "?"), r["texels"], r["matched"],
                                        r["shapes"], r["split"], r["missed"], r["spurious"], r["seconds"]),
                          file=sys.stderr, flush=True)
                results.append({"case": name, "orientation": orientation, "faces": faces, "rows": rows})
            if not args.keep:
                os.remove(mesh)
                os.remove(truth)
    seconds = time.time() - started
    with open(os.path.join(work, "results.json"), "w") as f:
        json.dump({"scales": scales, "auto": auto, "results": results}, f, indent=1)

    L = []
    series = ("r = " + ", ".join(pct(r) for r in scales)) if args.scales else \
        "r_k = 1% × 16^(k/11), k = 0 … 11"
    L.append("Made by `bench/experiments/scale_cases.py%s` on %s; geotex at commit %s%s; %d run(s) at once, %d "
             "thread(s) each; total %.0f s. Scales %s, of the largest bounding-box side; `geotex segment --scale r "
             "--orientation O` then `geotex evaluate`. Bold: the best fixed scale (most matched, then fewest "
             "spurious, then fewest split)." % (
                 "".join(" " + a for a in shown_args(sys.argv[1:])),
                 datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
                 git_commit(source_of(args.geotex)), "" if auto else " (no `--scale auto` in this geotex: no auto row)",
                 args.jobs, args.threads, seconds, series))
    L.append("")
    L += summary(results)
    for res in results:
        L += table(res["case"], res["orientation"], res["rows"], res["faces"])
    print("\n".join(L))
    if args.results:
        replace_section(args.results, BEGIN, END, L)
        print("scale_cases: replaced the scale-cases section of %s" % args.results, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
