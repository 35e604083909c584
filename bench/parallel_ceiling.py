#!/usr/bin/env python3
"""What two threads give on this machine, beside what they give the subdivision
(issue 16's 2-thread goal): the kernels of `examples/parallel_ceiling.rs` (no
sequential part at all: compute, random gather, fresh-memory faults, streaming writes)
and `qmesh subdivide --remove-outside` on 1 and 2 threads, all alternating in one run.
Prints a Markdown table of medians and the 2-thread speed-ups.

usage: bench/parallel_ceiling.py [--runs N] [--levels 7,8] [SURFACE...]"""
import argparse
import json
import os
import statistics

from common import DATA, Q, ROOT, sh

KERNELS = ["compute", "gather", "fault", "stream"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--levels", default="7,8")
    ap.add_argument("surfaces", nargs="*")
    a = ap.parse_args()
    sh("cargo", "build", "--release", "-q", "--manifest-path", os.path.join(ROOT, "Cargo.toml"))
    sh("cargo", "build", "--release", "-q", "--example", "parallel_ceiling", "-p", "qmesh",
       "--manifest-path", os.path.join(ROOT, "Cargo.toml"))
    kernels = os.path.join(ROOT, "target", "release", "examples", "parallel_ceiling")
    cases = [(s, int(l)) for s in (a.surfaces or ["armadillo.obj", "bunny.off"]) for l in a.levels.split(",")]
    times = {}  # (name, threads) -> [seconds]
    for _ in range(a.runs):
        for threads in (1, 2):
            env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
            out = json.loads(sh(kernels, env=env))
            for k in KERNELS:
                times.setdefault((k, threads), []).append(out[k])
            for surface, level in cases:
                src = surface if os.path.isabs(surface) else os.path.join(DATA, "surface", surface)
                res = json.loads(sh(Q, "subdivide", src, "--levels", str(level), "--remove-outside", "--json",
                                    "--force", "-o", f"/tmp/qmesh-ceiling-{threads}.vtk", env=env))
                name = f"subdivide {os.path.splitext(os.path.basename(src))[0]} L{level}"
                times.setdefault((name, threads), []).append(res["seconds"])
    print("| work | 1 thread s | 2 threads s | speed-up |")
    print("|---|--:|--:|--:|")
    for name in KERNELS + [n for n, t in times if t == 1 and n not in KERNELS]:
        one, two = (statistics.median(times[(name, t)]) for t in (1, 2))
        print(f"| {name} | {one:.3f} | {two:.3f} | {one / two:.2f} |")


main()
