#!/usr/bin/env python3
"""Run commands side by side; report median wall time and peak RSS (from wait4).

usage: measure.py RUNS LABEL -- CMD... [--- LABEL -- CMD...]...
Prints one JSON object per command with the median seconds, the max peak RSS, and the
command's own stdout (parsed when it is JSON) from one extra run."""
import json
import os
import statistics
import subprocess
import sys
import time


def measure(runs, cmd):
    walls, rss, last = [], 0, ""
    for _ in range(runs):
        t = time.perf_counter()
        pid = os.fork()
        if pid == 0:
            fd = os.open(os.devnull, os.O_WRONLY)
            os.dup2(fd, 1)
            os.dup2(fd, 2)
            os.execvp(cmd[0], cmd)
        _, status, usage = os.wait4(pid, 0)
        walls.append(time.perf_counter() - t)
        rss = max(rss, usage.ru_maxrss * 1024)
        if os.waitstatus_to_exitcode(status) != 0:
            sys.exit(f"command failed: {' '.join(cmd)}")
    out = subprocess.run(cmd, capture_output=True, text=True).stdout
    try:
        out = json.loads(out)
    except ValueError:
        pass
    return {"seconds": statistics.median(walls), "peak_rss_bytes": rss, "output": out}


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
    for g in groups:
        label, cmd = g[0], g[2:]
        r = measure(runs, cmd)
        r["label"] = label
        print(json.dumps(r))


main()
