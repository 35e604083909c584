#!/usr/bin/env python3
"""Octree subdivision in the shape of 2022 Table 1 (issue 16): query-replace against
hand-written boxes plus building the same map, on 1 and 2 threads, round-robin
(bench/measure.py).

For each surface and level: `qmesh subdivide --remove-outside` by query-replace on 2
threads and on 1 (RAYON_NUM_THREADS=1), `--direct` boxes, `qmesh info` on the direct
output (its build time: the map of the boxes as plain hexahedra) and `qmesh conformal`
on it (its `hanging` + `build` phases: the map of the boxes with the hanging vertices
inserted into the coarse faces, every face sewn, which is the map the query-replace
subdivision makes). Step times are the commands' own (`seconds`, `build_seconds`,
`phases`), the median over the runs as `authors_setup.py` takes them; wall times and
peak memory are the processes'. Prints a Markdown table:
volumes, #fqr, #vqr, the times, qr / (direct + map) for both maps and the speed-up of 2
threads over 1.

usage: bench/subdivision.py [--runs N] [--levels 6,7,8] [--out DIR] [SURFACE...]"""
import argparse
import json
import os
import sys

from common import DATA, MEASURE, Q, ROOT, median, sh
SURFACES = ["armadillo.obj", "bunny.off", "fertility.off", "cgal_mesh3.off"]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--levels", default="6,7,8")
    ap.add_argument("--out", default="/tmp/qmesh-subdivision")
    ap.add_argument("surfaces", nargs="*")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    sh("cargo", "build", "--release", "-q", "--manifest-path", os.path.join(ROOT, "Cargo.toml"))
    print("| surface | level | volumes | #fqr | #vqr | qr s (2 threads) | qr s (1 thread) | speed-up "
          "| direct s | map build s | direct + map s | qr / (direct + map) "
          "| same-map build s | qr / (direct + same map) | qr wall s | qr MB |")
    print("|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
    for name in a.surfaces or SURFACES:
        src = name if os.path.isabs(name) else os.path.join(DATA, "surface", name)
        stem = os.path.splitext(os.path.basename(src))[0]
        for level in [int(x) for x in a.levels.split(",")]:
            base = [Q, "subdivide", src, "--levels", str(level), "--remove-outside", "--json", "--force"]
            qr, direct = (os.path.join(a.out, f"{stem}_L{level}_{k}.vtk") for k in ("qr", "direct"))
            sh(*base, "--direct", "-o", direct)  # the file `info` reads
            res = sh(
                sys.executable, MEASURE, str(a.runs),
                "qr", "--", *base, "-o", qr, "---",
                "qr1", "--", "env", "RAYON_NUM_THREADS=1", *base, "-o", qr + "1.vtk", "---",
                "direct", "--", *base, "--direct", "-o", direct + "2.vtk", "---",
                "map", "--", Q, "info", direct, "--json", "---",
                "same", "--", Q, "conformal", direct, "--json", "--force", "-o", direct + "c.vtk",
            )
            q2, q1, d, m, c = [json.loads(line) for line in res.splitlines() if line.strip()]
            o = q2["output"]
            if o["volumes"] != d["output"]["volumes"] or o["volumes"] != q1["output"]["volumes"]:
                sys.exit(f"{stem} L{level}: the runs disagree on the volumes")
            qr2, qr1 = median(q2, lambda r: r["seconds"]), median(q1, lambda r: r["seconds"])
            direct_s = median(d, lambda r: r["seconds"])
            build = median(m, lambda r: r["build_seconds"])
            dm = direct_s + build
            same = median(c, lambda r: r["phases"]["hanging"] + r["phases"]["build"])
            ds = direct_s + same
            print(f"| {stem} | {level} | {o['volumes']:,} | {o['faces_replaced']:,} | {o['volumes_replaced']:,} "
                  f"| {qr2:.3f} | {qr1:.3f} | {qr1 / qr2:.2f} "
                  f"| {direct_s:.3f} | {build:.3f} | {dm:.3f} "
                  f"| {qr2 / dm:.2f} | {same:.3f} | {qr2 / ds:.2f} "
                  f"| {q2['seconds']:.2f} | {q2['peak_rss_bytes'] / 1e6:.0f} |", flush=True)


main()
