#!/usr/bin/env python3
"""The conformal and tet2hex pipelines before and after (issue 16 item 3): the same
commands with an earlier qmesh binary (--old) and the current one, round-robin, with
the current one's phase timings (`--json` "phases").

Inputs: S3 (cgal_mesh3.off) and bunny octrees at level 7 (`subdivide --margin 0
--remove-outside`), conformal with the authors' 325 + square-5 patterns and with qmesh's
generated transitions; tet2hex of the shared bunny and CAD0 tetrahedral meshes.

usage: bench/pipelines.py --old BINARY [--runs N] [--out DIR]
(an earlier binary: `git worktree add /tmp/old REV && cargo build --release` there)"""
import argparse
import json
import os
import statistics
import tempfile

from common import DATA, Q, ROOT, sh, timed

def run(cmd):
    """Wall seconds, peak RSS bytes and stdout of one run of cmd (conformal exits 1 when a
    cell is left unmatched: that is a result, not a failure)."""
    return timed(cmd, ok=(0, 1))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--old", required=True)
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    out = a.out or tempfile.mkdtemp(prefix="qmesh-pipelines-")
    os.makedirs(out, exist_ok=True)
    sh("cargo", "build", "--release", "--quiet", cwd=ROOT)
    p325 = ",".join(os.path.join(DATA, "patterns", "cgal", p) for p in ["hexa-325-patterns", "square-5-patterns"])
    octrees = {}
    for name, surface in [("S3", "cgal_mesh3.off"), ("bunny", "bunny.off")]:
        octrees[name] = os.path.join(out, f"{name}_l7.vtk")
        sh(Q, "subdivide", os.path.join(DATA, "surface", surface), "--levels", "7", "--margin", "0",
           "--remove-outside", "-o", octrees[name], "--force", "-q")
    experiments = []
    for name, octree in octrees.items():
        experiments.append((f"conformal {name} L7, 325 patterns", ["conformal", octree, "--patterns", p325]))
        experiments.append((f"conformal {name} L7, generated", ["conformal", octree]))
    for tets in ["bunny.mesh", "CAD0.mesh"]:
        experiments.append((f"tet2hex {tets}", ["tet2hex", os.path.join(DATA, "tet", tets)]))
    samples = {}
    for _ in range(a.runs):
        for label, args in experiments:
            for tool, binary in [("old", a.old), ("new", Q)]:
                target = os.path.join(out, f"{tool}.vtk")
                w, m, stdout = run([binary, *args, "-o", target, "--force", "--json"])
                samples.setdefault((label, tool), []).append((w, m, stdout))
    print(f"{a.runs} runs, round-robin, medians; old = {a.old}\n")
    print("| pipeline | old wall s | new wall s | old/new | old MB | new MB | new phases (s) |")
    print("|---|--:|--:|--:|--:|--:|---|")
    for label, _ in experiments:
        old, new = samples[(label, "old")], samples[(label, "new")]
        wo, wn = statistics.median(x[0] for x in old), statistics.median(x[0] for x in new)
        mo, mn = max(x[1] for x in old), max(x[1] for x in new)
        phases = json.loads(new[-1][2]).get("phases", {})
        listed = ", ".join(f"{k} {v:.3f}" for k, v in sorted(phases.items(), key=lambda kv: -kv[1]) if k != "total")
        print(f"| {label} | {wo:.2f} | {wn:.2f} | {wo / wn:.2f} | {mo / 1e6:.0f} | {mn / 1e6:.0f} | {listed} |")


if __name__ == "__main__":
    main()
