#!/usr/bin/env python3
"""Run commands side by side; report median wall time and peak RSS.

usage: measure.py RUNS LABEL -- CMD... [--- LABEL -- CMD...]...
The commands run round-robin (one run of each, RUNS times), so a shared machine that
speeds up or slows down during the measurement affects them alike. Prints one JSON
object per command with the median seconds, the max peak RSS, the command's own
stdout (parsed when it is JSON) of every run (`outputs`, to take medians of the times
a command reports itself) and of its median run (`output`).

Peak RSS comes from GNU time (/usr/bin/time), which forks the command from its own
small process: a command forked from Python directly would be charged Python's
resident pages (~10 MB) until its exec, which swamps small runs."""
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time


GNU_TIME = "/usr/bin/time"


def run_once(cmd):
    """Wall seconds, peak RSS bytes and stdout of one run of cmd."""
    if not os.access(GNU_TIME, os.X_OK):
        sys.exit(f"{GNU_TIME} (GNU time, Debian package `time`) is needed for peak memory")
    with tempfile.NamedTemporaryFile("r") as report:
        t = time.perf_counter()
        done = subprocess.run([GNU_TIME, "-f", "%M", "-o", report.name, *cmd],
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        wall = time.perf_counter() - t
        if done.returncode != 0:
            sys.exit(f"command failed: {' '.join(cmd)}")
        kib = int(report.read().split()[-1])
    return wall, kib * 1024, parsed(done.stdout)


def parsed(out):
    try:
        return json.loads(out)
    except ValueError:
        return out


def main():
    runs = int(sys.argv[1])
    groups, cur = [], []
    for a in sys.argv[2:]:
        if a == "---":
            groups.append(cur)
            cur = []
        else:
            cur.append(a)
    groups.append(cur)
    walls = [[] for _ in groups]
    outputs = [[] for _ in groups]
    rss = [0 for _ in groups]
    for _ in range(runs):
        for k, g in enumerate(groups):
            w, m, out = run_once(g[2:])
            walls[k].append(w)
            outputs[k].append(out)
            rss[k] = max(rss[k], m)
    for k, g in enumerate(groups):
        median_run = sorted(range(runs), key=lambda i: walls[k][i])[runs // 2]
        r = {"seconds": statistics.median(walls[k]), "peak_rss_bytes": rss[k], "output": outputs[k][median_run],
             "outputs": outputs[k], "label": g[0]}
        print(json.dumps(r))


main()
