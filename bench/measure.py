#!/usr/bin/env python3
"""Run commands side by side; report median wall time and peak RSS (from wait4).

usage: measure.py RUNS LABEL -- CMD... [--- LABEL -- CMD...]...
The commands run round-robin (one run of each, RUNS times), so a shared machine that
speeds up or slows down during the measurement affects them alike. Prints one JSON
object per command with the median seconds, the max peak RSS, and the command's own
stdout (parsed when it is JSON) from one extra run."""
import json
import os
import statistics
import subprocess
import sys
import time


def run_once(cmd):
    """Wall seconds and peak RSS bytes of one run of cmd (output discarded)."""
    t = time.perf_counter()
    pid = os.fork()
    if pid == 0:
        fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(fd, 1)
        os.dup2(fd, 2)
        os.execvp(cmd[0], cmd)
    _, status, usage = os.wait4(pid, 0)
    wall = time.perf_counter() - t
    if os.waitstatus_to_exitcode(status) != 0:
        sys.exit(f"command failed: {' '.join(cmd)}")
    return wall, usage.ru_maxrss * 1024


def output_of(cmd):
    out = subprocess.run(cmd, capture_output=True, text=True).stdout
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
    rss = [0 for _ in groups]
    for _ in range(runs):
        for k, g in enumerate(groups):
            w, m = run_once(g[2:])
            walls[k].append(w)
            rss[k] = max(rss[k], m)
    for k, g in enumerate(groups):
        r = {"seconds": statistics.median(walls[k]), "peak_rss_bytes": rss[k], "output": output_of(g[2:]), "label": g[0]}
        print(json.dumps(r))


main()
