#!/usr/bin/env python3
"""The performance benchmark (make bench-perf): stage times, end-to-end time and peak memory of
`geotex segment` on the synthetic sphere-1 (icosphere levels 5 to 9) at the scales 0.02, 0.04
and 0.08, and on real meshes from Debian's libcgal-demo; beside it, MeshLab's comparable work
(Laplacian smoothing and a Hausdorff distance, bench/perf/smooth_hausdorff.mlx) on the same
meshes. Every configuration runs in its own process, so its peak RSS is its own; a run longer
than --timeout is killed and reported as a timeout.

  bench/perf/run_perf.py [--geotex build/geotex] [--results bench/RESULTS.md]
  bench/perf/run_perf.py --tiny [--geotex build/geotex]     (CI: small, no RESULTS.md change)

The full run replaces the part of RESULTS.md between <!-- perf:begin --> and <!-- perf:end -->
(creating the file with its markers if needed) and nothing else. With --tiny it writes to a
temporary directory, prints the tables and exits 1 unless every row has numbers. Not a test of
speed: no number fails it. Only the Python standard library is used.
"""

import argparse
import datetime
import os
import re
import shutil
import signal
import subprocess
import sys
import tarfile
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
MLX = os.path.join(HERE, "smooth_hausdorff.mlx")
CGAL_DATA = "/usr/share/doc/libcgal-dev/data.tar.gz"  # package libcgal-demo
CGAL_MESHES = ["bunny00.off", "dino.off", "fandisk.off", "ChineseDragon-10kv.off",
               "refined_elephant.off"]
BEGIN, END = "<!-- perf:begin -->", "<!-- perf:end -->"

# Columns of the stage breakdown, matched as prefixes of geotex's "geotex: <stage>  <t> s"
# lines; any other stage goes to "other".
STAGES = [("read", "reading"), ("repair", "repair"), ("topology", "topology"),
          ("smoothing", "smoothing"), ("depth map", "depth map"), ("texels", "texels"),
          ("curvature", "curvature"), ("features", "features"), ("clustering", "clustering"),
          ("write", "writing")]
STAGE_LINE = re.compile(r"^geotex: (\S.*?)\s+([0-9.]+) s\s*$")
SUMMARY = re.compile(r"(\d+) texels? in (\d+) textures?")


def log(msg):
    print(f"bench-perf: {msg}", file=sys.stderr, flush=True)


class Run:
    """One process: wall seconds, peak RSS (MB, of this process alone), exit status, output."""

    def __init__(self, cmd, timeout, env=None, cwd=None):
        t0 = time.monotonic()
        with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
            p = subprocess.Popen(cmd, stdout=out, stderr=err, env=env, cwd=cwd,
                                 start_new_session=True)
            killed = []

            def kill():
                killed.append(True)
                try:
                    os.killpg(p.pid, signal.SIGKILL)  # the group of the process started above
                except ProcessLookupError:
                    pass

            timer = threading.Timer(timeout, kill)
            timer.start()
            _, status, usage = os.wait4(p.pid, 0)
            timer.cancel()
            p.returncode = os.waitstatus_to_exitcode(status)
            self.seconds = time.monotonic() - t0
            self.peak_mb = usage.ru_maxrss / 1024.0  # KB on Linux
            self.timed_out = bool(killed)
            self.code = p.returncode
            out.seek(0)
            err.seek(0)
            self.stdout = out.read().decode(errors="replace")
            self.stderr = err.read().decode(errors="replace")

    @property
    def ok(self):
        return self.code == 0 and not self.timed_out

    def failure(self):
        if self.timed_out:
            return "timeout"
        last = (self.stderr.strip().splitlines() or ["?"])[-1]
        return f"failed (exit {self.code}: {last[:80]})"


def fmt(x, digits=3):
    return "–" if x is None else f"{x:.{digits}f}"


def count_faces(path):
    """Face count from the header of a PLY or OFF file (no full parse)."""
    with open(path, "rb") as f:
        head = f.read(4096).decode("latin-1")
    m = re.search(r"element face (\d+)", head)
    if m:
        return int(m.group(1))
    toks = [t for line in head.splitlines() for t in line.split("#")[0].split()]
    if toks and toks[0].endswith("OFF"):
        return int(toks[2])
    return None


class Bench:
    def __init__(self, args):
        self.args = args
        self.geotex = args.geotex
        self.work = tempfile.mkdtemp(prefix="geotex-perf-")
        help_text = subprocess.run([self.geotex, "segment", "--help"], capture_output=True,
                                   text=True).stdout
        self.has_disc = "--disc" in help_text
        if args.modes:
            self.modes = args.modes.split(",")
        else:
            self.modes = ["auto", "fast", "exact"] if self.has_disc else ["default"]
        if not self.has_disc and self.modes != ["default"]:
            sys.exit("bench-perf: this geotex has no --disc option; use --modes default")
        self.rows = []       # dicts: mesh, faces, scale, mode, run or skip reason
        self.meshlab = []    # dicts: mesh, faces, io run, full run
        self.notes = []
        self.timed_out = {}  # mode -> list of (level, scale) that timed out
        self.xvfb = None
        self.ml_env = None

    # ---- geotex ------------------------------------------------------------------------------
    def segment(self, name, path, faces, scale, level=None):
        for mode in self.modes:
            row = dict(mesh=name, faces=faces, scale=scale, mode=mode, level=level, run=None,
                       skip=None)
            if level is not None and any(lv <= level and sc <= scale
                                         for lv, sc in self.timed_out.get(mode, [])):
                row["skip"] = "skipped (a smaller run timed out)"
                self.rows.append(row)
                log(f"{name} scale {scale} {mode}: skipped")
                continue
            cmd = [self.geotex, "segment", path, "--scale", str(scale),
                   "-o", os.path.join(self.work, "out.ply")]
            if self.args.threads:
                cmd += ["--threads", str(self.args.threads)]
            if mode != "default":
                cmd += ["--disc", mode]
            run = Run(cmd, self.args.timeout)
            row["run"] = run
            if run.ok:
                stages = {col: 0.0 for col, _ in STAGES}
                stages["other"] = 0.0
                for line in run.stderr.splitlines():
                    m = STAGE_LINE.match(line)
                    if not m:
                        continue
                    col = next((c for c, pre in STAGES if m.group(1).startswith(pre)), "other")
                    stages[col] += float(m.group(2))
                row["stages"] = stages
                m = SUMMARY.search(run.stdout + run.stderr)
                row["texels"] = int(m.group(1)) if m else None
                log(f"{name} scale {scale} {mode}: {run.seconds:.2f} s, {run.peak_mb:.0f} MB")
            else:
                if run.timed_out and level is not None:
                    self.timed_out.setdefault(mode, []).append((level, scale))
                log(f"{name} scale {scale} {mode}: {run.failure()}")
            self.rows.append(row)

    # ---- MeshLab -----------------------------------------------------------------------------
    def start_meshlab(self):
        if self.args.no_meshlab:
            self.notes.append("MeshLab not run (--no-meshlab).")
            return False
        if not shutil.which("meshlabserver"):
            msg = "MeshLab not run: meshlabserver not installed (Debian package meshlab)."
            self.notes.append(msg)
            log(msg)
            return False
        if not shutil.which("Xvfb"):
            msg = ("MeshLab not run: meshlabserver needs an X display (with "
                   "QT_QPA_PLATFORM=offscreen it aborts: 'GLEW initialization failed: Missing GL "
                   "version') and Xvfb (package xvfb) is not installed.")
            self.notes.append(msg)
            log(msg)
            return False
        # Our own Xvfb for the whole run, so its start-up is not in MeshLab's times.
        r, w = os.pipe()
        self.xvfb = subprocess.Popen(["Xvfb", "-displayfd", str(w), "-nolisten", "tcp",
                                      "-screen", "0", "640x480x24"], pass_fds=(w,),
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(w)
        display = b""
        while not display.endswith(b"\n"):
            chunk = os.read(r, 64)
            if not chunk:
                break
            display += chunk
        os.close(r)
        if not display.strip():
            self.notes.append("MeshLab not run: Xvfb did not start.")
            return False
        xdg = os.path.join(self.work, "xdg")
        os.mkdir(xdg, 0o700)
        self.ml_env = dict(os.environ, DISPLAY=":" + display.decode().strip(),
                           XDG_RUNTIME_DIR=xdg)
        version = subprocess.run(["dpkg-query", "-W", "-f=${Version}", "meshlab"],
                                 capture_output=True, text=True).stdout or "?"
        self.meshlab_version = version
        return True

    def stop_meshlab(self):
        if self.xvfb:
            self.xvfb.terminate()
            self.xvfb.wait()
            self.xvfb = None

    def run_meshlab(self, name, path, faces):
        out = os.path.join(self.work, "meshlab-out.ply")
        io = Run(["meshlabserver", "-i", path, "-o", out], self.args.timeout, env=self.ml_env,
                 cwd=self.work)
        full = Run(["meshlabserver", "-i", path, "-o", out, "-s", MLX], self.args.timeout,
                   env=self.ml_env, cwd=self.work)
        if full.ok and "Hausdorff Distance computed" not in full.stdout + full.stderr:
            full.code, full.stderr = -1, "no 'Hausdorff Distance computed' in MeshLab's log"
        self.meshlab.append(dict(mesh=name, faces=faces, io=io, full=full))
        log(f"{name} MeshLab: load+save {fmt(io.seconds, 2) if io.ok else io.failure()}, "
            f"smooth+Hausdorff {fmt(full.seconds, 2) if full.ok else full.failure()}")

    # ---- the plan ----------------------------------------------------------------------------
    def run(self):
        a = self.args
        ml = self.start_meshlab()
        try:
            for level in a.levels:
                path = os.path.join(self.work, f"sphere1-level{level}.ply")
                r = Run([self.geotex, "synth", "--level", str(level), "-o", path, "--quiet"],
                        a.timeout)
                if not r.ok:
                    sys.exit(f"bench-perf: geotex synth --level {level}: {r.failure()}")
                faces = count_faces(path)
                name = f"sphere-1 level {level}"
                for scale in a.scales:
                    self.segment(name, path, faces, scale, level=level)
                if ml and level in a.meshlab_levels:
                    self.run_meshlab(name, path, faces)
                for f in (path, path[:-4] + ".truth.json"):
                    if os.path.exists(f):
                        os.remove(f)
            for mesh in self.cgal_meshes():
                faces = count_faces(mesh)
                name = os.path.basename(mesh)
                for scale in a.cgal_scales:
                    self.segment(name, mesh, faces, scale)
                if ml:
                    self.run_meshlab(name, mesh, faces)
        finally:
            self.stop_meshlab()

    def cgal_meshes(self):
        if not self.args.cgal:
            return []
        if not os.path.exists(CGAL_DATA):
            msg = f"CGAL demo meshes not run: {CGAL_DATA} missing (Debian package libcgal-demo)."
            self.notes.append(msg)
            log(msg)
            return []
        wanted = [f"data/meshes/{m}" for m in self.args.cgal]
        with tarfile.open(CGAL_DATA) as t:
            members = [t.getmember(w) for w in wanted]
            t.extractall(self.work, members=members)
        return [os.path.join(self.work, w) for w in wanted]

    # ---- report ------------------------------------------------------------------------------
    def stage_table(self, rows, first):
        cols = [c for c, _ in STAGES]
        if any(r.get("stages", {}).get("other") for r in rows):
            cols.append("other")
        head = ([first, "faces", "scale"] + (["disc"] if self.has_disc else []) + cols +
                ["**total s**", "peak RSS MB", "texels found", "dominant stage"])
        lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        for r in rows:
            lead = [r["mesh"].replace("sphere-1 level ", ""), f"{r['faces']:,}", f"{r['scale']:g}"]
            lead += [r["mode"]] if self.has_disc else []
            run = r["run"]
            if r["skip"] or not run.ok:
                why = r["skip"] or (f"timeout (> {self.args.timeout:g} s)" if run.timed_out
                                    else run.failure())
                cells = ["–"] * len(cols) + [why, "–", "–", "–"]
            else:
                st = r["stages"]
                dom = max(cols, key=lambda c: st.get(c, 0.0))
                share = st[dom] / run.seconds * 100 if run.seconds > 0 else 0
                cells = [fmt(st.get(c, 0.0)) for c in cols]
                cells += [f"**{run.seconds:.3f}**", f"{run.peak_mb:.0f}",
                          str(r["texels"]) if r["texels"] is not None else "?",
                          f"{dom} ({share:.0f}%)"]
            lines.append("| " + " | ".join(lead + cells) + " |")
        return lines

    def find(self, mesh, scale, mode):
        for r in self.rows:
            if r["mesh"] == mesh and abs(r["scale"] - scale) < 1e-12 and r["mode"] == mode:
                return r
        return None

    @staticmethod
    def seconds(row):
        return row["run"].seconds if row and row["run"] and row["run"].ok else None

    def meshlab_table(self):
        head = ["mesh", "faces", "MeshLab load+save s", "MeshLab smooth+Hausdorff s",
                "of which filters s", "MeshLab peak RSS MB"]
        for mode in self.modes:
            label = f" ({mode})" if self.has_disc else ""
            head += [f"geotex segment 4%{label} s", f"ratio geotex/MeshLab{label}"]
        lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        for m in self.meshlab:
            io, full = m["io"], m["full"]
            cells = [m["mesh"].replace("sphere-1 level ", "level "), f"{m['faces']:,}",
                     fmt(io.seconds, 2) if io.ok else io.failure(),
                     fmt(full.seconds, 2) if full.ok else full.failure(),
                     fmt(full.seconds - io.seconds, 2) if full.ok and io.ok else "–",
                     f"{full.peak_mb:.0f}" if full.ok else "–"]
            for mode in self.modes:
                g = self.seconds(self.find(m["mesh"], 0.04, mode))
                cells += [fmt(g, 2), f"{g / full.seconds:.2f}" if g and full.ok else "–"]
            lines.append("| " + " | ".join(cells) + " |")
        return lines

    def targets(self):
        lines = ["| target (issue 4) | " + " | ".join(
            (f"disc {m}" if self.has_disc else "measured") for m in self.modes) + " |",
                 "|---|" + "---|" * len(self.modes)]

        def verdict(ok, text):
            return f"{'**met**' if ok else '**not met**'}: {text}"

        def cell_time(level, scale, mode, limit_s, limit_mb=None):
            r = self.find(f"sphere-1 level {level}", scale, mode)
            if r is None:
                return "not measured"
            if r["skip"]:
                return "**not met**: " + r["skip"]
            if not r["run"].ok:
                return "**not met**: " + (f"timeout (> {self.args.timeout:g} s)"
                                          if r["run"].timed_out else r["run"].failure())
            s, mb = r["run"].seconds, r["run"].peak_mb
            ok = s <= limit_s and (limit_mb is None or mb <= limit_mb)
            return verdict(ok, f"{s:.2f} s" + (f", {mb:.0f} MB" if limit_mb else ""))

        def cell_ratio(mode):
            lo = self.seconds(self.find("sphere-1 level 8", 0.02, mode))
            hi_row = self.find("sphere-1 level 8", 0.08, mode)
            hi = self.seconds(hi_row)
            if lo is None or hi_row is None:
                return "not measured"
            if hi is None:
                return f"**not met**: 2% {lo:.2f} s, 8% did not finish"
            return verdict(hi <= 2 * lo, f"{hi:.2f} s / {lo:.2f} s = {hi / lo:.2f}×")

        lines.append("| level 7 at 4%, end to end ≤ 1 s | " +
                     " | ".join(cell_time(7, 0.04, m, 1.0) for m in self.modes) + " |")
        lines.append("| level 9 at 4% ≤ 30 s and ≤ 3 GB peak | " +
                     " | ".join(cell_time(9, 0.04, m, 30.0, 3 * 1024) for m in self.modes) + " |")
        lines.append("| level 8: time at 8% ≤ 2× time at 2% | " +
                     " | ".join(cell_ratio(m) for m in self.modes) + " |")
        # Where the level-7 time goes (the default mode's run).
        r = self.find("sphere-1 level 7", 0.04, self.modes[0])
        if r is not None and not r["skip"] and r["run"].ok:
            st, total = r["stages"], r["run"].seconds
            parts = sorted(((t, c) for c, t in st.items() if t > 0), reverse=True)
            outside = total - sum(st.values())
            lines += ["", f"Level 7 at 4% ({self.modes[0]}), where the {total:.2f} s go on "
                      f"{self.args.threads or os.cpu_count()} threads: " +
                      ", ".join(f"{c} {t:.3f} s" for t, c in parts) +
                      (f", process start, exit and the summary {outside:.3f} s" if outside > 0.0005 else "") +
                      ". The two largest are the smoothing (exact discs of about 270 vertices, walked "
                      "cluster by cluster: docs/disc-means.md) and the depth map (CGAL AABB trees over "
                      "two halves of the smoothed surface, built in parallel, then queried in parallel)."]
        return lines

    def report(self, command, load_before, load_after, started, elapsed):
        a = self.args
        mem = 0
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemTotal"):
                    mem = int(line.split()[1]) / 1048576
        cpu = "?"
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
        git = lambda *x: subprocess.run(["git", "-C", TOP, *x], capture_output=True,
                                        text=True).stdout.strip()
        commit = git("rev-parse", "--short", "HEAD") or "?"
        dirty = " plus uncommitted changes" if git("status", "--porcelain", "--untracked-files=no") else ""
        synth = [r for r in self.rows if r["level"] is not None]
        real = [r for r in self.rows if r["level"] is None]
        threads = a.threads or os.cpu_count()
        modes = (f"Disc modes {', '.join(self.modes)} (`--disc`; auto is the default), each "
                 "in the same run"
                 if self.has_disc else
                 "One disc mode: this geotex has no `--disc` option, so every run is the exact "
                 "(naive) disc walk")
        out = [BEGIN, "", "## Performance (`make bench-perf`)", "",
               f"Machine: {os.cpu_count()} cores ({cpu}), {mem:.0f} GiB memory; "
               f"{started:%Y-%m-%d %H:%M} UTC; commit {commit}{dirty}; "
               f"load average (1, 5, 15 min) before {load_before}, after {load_after} "
               "(other jobs on the machine inflate the times).", "",
               f"Command: `{command}` ({elapsed / 60:.1f} min). Each configuration is one "
               f"`geotex segment MESH --scale S -o OUT.ply` process on {threads} threads; "
               "**total** is its wall time from start to exit (read to write); the stage columns "
               "are the times geotex prints; peak RSS is that process's own (wait4). "
               f"{modes}. A run over {a.timeout:g} s is killed and shown as a timeout; larger "
               "runs of the same mode are then skipped.", "",
               ]
        if not a.tiny:
            out += ["### Targets", ""] + self.targets() + [""]
        out += ["### Synthetic sphere-1, stage times in seconds", ""] + self.stage_table(
            synth, "level")
        if real:
            out += ["", "### CGAL demo meshes (Debian libcgal-demo, data/meshes), seconds", ""]
            out += self.stage_table(real, "mesh")
        out += ["", "### MeshLab on the same meshes", ""]
        if self.meshlab:
            out += [f"MeshLab {self.meshlab_version}, `meshlabserver -i IN -o OUT.ply -s "
                    "bench/perf/smooth_hausdorff.mlx` (duplicate the layer, 10 steps of "
                    "Laplacian smoothing, Hausdorff distance from every original vertex to the "
                    "smoothed surface) in its own process on an Xvfb display started once "
                    "for the run (meshlabserver needs OpenGL: with QT_QPA_PLATFORM=offscreen it "
                    "aborts with 'GLEW initialization failed'). \"load+save\" is meshlabserver "
                    "with no script, the floor of its process start, reading and writing; the "
                    "ratio divides geotex's whole `segment` run at scale 0.04 by MeshLab's whole "
                    "smooth+Hausdorff run (above 1: geotex slower).", ""]
            out += self.meshlab_table()
        out += [f"\n{n}" for n in self.notes]
        out += ["", END]
        return "\n".join(out) + "\n"

    def all_numbers(self):
        ok = all(r["run"] is not None and r["run"].ok for r in self.rows) and self.rows
        ok = ok and all(m["io"].ok and m["full"].ok for m in self.meshlab)
        return bool(ok)


def write_results(path, section):
    if os.path.exists(path):
        with open(path) as f:
            text = f.read()
    else:
        text = ("# geotex results\n\nWritten by the benchmarks; each section is replaced by its "
                "own command only.\n\n<!-- experiments:begin -->\n<!-- experiments:end -->\n\n"
                f"{BEGIN}\n{END}\n")
    if BEGIN in text and END in text and text.index(BEGIN) < text.index(END):
        i, j = text.index(BEGIN), text.index(END) + len(END)
        text = text[:i] + section.rstrip("\n") + text[j:]
    else:
        text = text.rstrip("\n") + "\n\n" + section
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--geotex", default=os.path.join(TOP, "build", "geotex"))
    ap.add_argument("--results", default=os.path.join(TOP, "bench", "RESULTS.md"))
    ap.add_argument("--tiny", action="store_true",
                    help="levels 4 and 5 at scale 0.04, dino.off and MeshLab if installed; "
                         "prints only; exit 1 unless every row has numbers")
    ap.add_argument("--levels", default="5,6,7,8,9")
    ap.add_argument("--scales", default="0.02,0.04,0.08")
    ap.add_argument("--meshlab-levels", default="5,6,7,8,9")
    ap.add_argument("--modes", help="disc modes to run (default: auto,fast,exact if geotex has --disc)")
    ap.add_argument("--timeout", type=float, default=300, help="seconds per run")
    ap.add_argument("--threads", type=int, default=0, help="geotex --threads (default all)")
    ap.add_argument("--no-meshlab", action="store_true")
    a = ap.parse_args()
    command = "make bench-perf" if not a.tiny else "bench/perf/run_perf.py --tiny"
    if len(sys.argv) > 1 and not a.tiny and os.environ.get("MAKELEVEL") is None:
        command = "bench/perf/run_perf.py " + " ".join(sys.argv[1:])
    if a.tiny:
        a.levels, a.scales, a.meshlab_levels = "4,5", "0.04", "5"
        a.timeout = min(a.timeout, 60)
        a.cgal, a.cgal_scales = ["dino.off"], [0.04]
    else:
        a.cgal, a.cgal_scales = CGAL_MESHES, [float(s) for s in a.scales.split(",")]
    a.levels = [int(x) for x in a.levels.split(",")]
    a.scales = [float(x) for x in a.scales.split(",")]
    a.meshlab_levels = [int(x) for x in a.meshlab_levels.split(",")]
    if not os.access(a.geotex, os.X_OK):
        sys.exit(f"bench-perf: {a.geotex} is not an executable (build first, or --geotex)")

    started = datetime.datetime.now(datetime.timezone.utc)
    t0 = time.monotonic()
    load_before = ", ".join(f"{x:.2f}" for x in os.getloadavg())
    b = Bench(a)
    try:
        b.run()
        load_after = ", ".join(f"{x:.2f}" for x in os.getloadavg())
        section = b.report(command, load_before, load_after, started, time.monotonic() - t0)
    finally:
        shutil.rmtree(b.work, ignore_errors=True)
    print(section)
    if a.tiny:
        if not b.all_numbers():
            print("bench-perf --tiny: FAILED: a row has no numbers (see above)", file=sys.stderr)
            return 1
        print("bench-perf --tiny: ok, every row has numbers", file=sys.stderr)
        return 0
    write_results(a.results, section)
    log(f"wrote the perf section of {a.results}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
