"""Helpers shared by the experiment scripts of bench/experiments/ (run_experiments.py, the
paper's experiments, words.py, the words experiment, scale_cases.py, issue 20's cases, and
landmarks.py, the clustering of many texels; stage_per_face.py and series_stages.py, the stage
times): running a command, the synthetic sphere, the commit and the source tree of a build, the
marked section of bench/RESULTS.md, the adjusted Rand index, and the stage lines geotex prints.
"""

import os
import re
import subprocess
import sys
import time

# A stage's time as geotex prints it on stderr: "geotex: depth map (positive)   0.123 s".
STAGE_LINE = re.compile(r"^geotex: (\S.*?)\s+([0-9.]+) s\s*$")


def run_checked(cmd):
    """Runs `cmd`; on failure prints it with its output and exits 1. Returns (stdout, seconds)."""
    t0 = time.time()
    res = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if res.returncode != 0:
        sys.stderr.write("command failed (exit %d): %s\n%s%s" % (res.returncode, " ".join(cmd), res.stdout, res.stderr))
        raise SystemExit(1)
    return res.stdout, time.time() - t0


def synth_command(geotex, mesh, truth, level, noise=0.0, seed=1, layout=1, engraved=0.0):
    """`geotex synth` of sphere-1 with its ground truth."""
    cmd = [geotex, "synth", "-o", mesh, "--truth", truth, "--level", str(level), "--quiet",
           "--noise", repr(noise), "--noise-seed", str(seed), "--layout-seed", str(layout)]
    if engraved:
        cmd += ["--engraved", repr(engraved)]
    return cmd


def git_commit(where):
    """Short commit of the tree at `where`, marked when it has uncommitted changes; '?' if none."""
    try:
        rev = subprocess.run(["git", "-C", where, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", where, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return rev + (" (with uncommitted changes)" if dirty else "") if rev else "?"
    except OSError:
        return "?"


def source_of(binary):
    """The source tree a CMake-built binary came from (CMAKE_HOME_DIRECTORY of its build), else
    the repository holding these scripts."""
    cache = os.path.join(os.path.dirname(os.path.abspath(binary)), "CMakeCache.txt")
    try:
        with open(cache) as f:
            for line in f:
                if line.startswith("CMAKE_HOME_DIRECTORY:"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def replace_section(path, begin, end, lines, new_file=None):
    """Replaces the text between the markers `begin` and `end` of `path` by `lines` (appends
    the section when the markers are missing), atomically. A missing file is started from
    `new_file` (a text holding the markers) when given."""
    section = begin + "\n" + "\n".join(lines) + "\n" + end
    if os.path.exists(path) or new_file is None:
        with open(path) as f:
            text = f.read()
    else:
        text = new_file
    if begin in text and end in text and text.index(begin) < text.index(end):
        head, rest = text.split(begin, 1)
        text = head + section + rest.split(end, 1)[1]
    else:
        text = text.rstrip("\n") + "\n\n" + section + "\n"
    tmp = path + ".tmp.%d" % os.getpid()
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def adjusted_rand(a, b):
    """Adjusted Rand index of two labellings (Hubert & Arabie 1985); 1 for identical
    partitions, also when both have one group."""
    n = len(a)
    if n < 2:
        return 1.0
    comb = lambda x: x * (x - 1) / 2.0
    pairs, ca, cb = {}, {}, {}
    for x, y in zip(a, b):
        pairs[(x, y)] = pairs.get((x, y), 0) + 1
        ca[x] = ca.get(x, 0) + 1
        cb[y] = cb.get(y, 0) + 1
    index = sum(comb(v) for v in pairs.values())
    sa, sb = sum(comb(v) for v in ca.values()), sum(comb(v) for v in cb.values())
    expected = sa * sb / comb(n)
    top = 0.5 * (sa + sb)
    return 1.0 if top == expected else (index - expected) / (top - expected)
