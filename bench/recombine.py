#!/usr/bin/env python3
"""2025 Table 1 for qmesh: tetrahedralize the shared hex meshes (--five and --any), then
recombine them with qmesh and with HXT's combination (hxt_combine) on the same file,
round-robin (bench/measure.py), and print a Markdown table with ratios.

usage: bench/recombine.py [--runs N] [--out DIR] [MESH...]   (default: every hex mesh)"""
import argparse
import glob
import json
import os
import sys

from common import DATA, MEASURE, Q, sh
HXT = os.path.join(os.path.dirname(DATA), "peers", "hxt_combine")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--out", default="/tmp/qmesh-recombine")
    ap.add_argument("meshes", nargs="*")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    if a.meshes:
        meshes = a.meshes
    else:
        # Every hex mesh once: the .mesh files, and the .vtk files without a .mesh twin.
        mesh = sorted(glob.glob(os.path.join(DATA, "hex", "*.mesh")))
        stems = {os.path.splitext(os.path.basename(m))[0] for m in mesh}
        vtk = [v for v in sorted(glob.glob(os.path.join(DATA, "hex", "*.vtk")))
               if os.path.splitext(os.path.basename(v))[0] not in stems | {"rockarm"}]
        meshes = mesh + vtk
    rows = []
    for src in meshes:
        name = os.path.splitext(os.path.basename(src))[0]
        for choice in ["five", "any"]:
            tets = os.path.join(a.out, f"{name}_{choice}.mesh")
            t = json.loads(sh(Q, "tetrahedralize", src, "-o", tets, f"--{choice}", "--json", "--force"))["report"]
            out = os.path.join(a.out, f"{name}_{choice}_hex.mesh")
            res = sh(
                sys.executable, MEASURE, str(a.runs),
                "qmesh", "--", Q, "recombine", tets, "-o", out, "--json", "--force", "---",
                # HXT writes its hexahedra too: both runs do the same work.
                "hxt", "--", HXT, tets, "--out", os.path.join(a.out, f"{name}_{choice}_hxt.mesh"),
                "--quiet", "--threads", "2",
            )
            q, h = [json.loads(line) for line in res.splitlines() if line.strip()]
            qr = q["output"]["recombine"]
            rows.append({
                "mesh": name, "split": choice, "hexes_in": t["hexes"], "tets": t["tets"],
                "q_Q": qr["candidates"], "q_h": qr["hexes"], "q_t": qr["tets_left"],
                "q_mb": q["peak_rss_bytes"] / 1e6, "q_s": q["seconds"],
                "h_Q": h["output"]["candidate_hexes"], "h_h": h["output"]["hexes"], "h_t": h["output"]["tets_left"],
                "h_mb": h["peak_rss_bytes"] / 1e6, "h_s": h["seconds"],
            })
            print(json.dumps(rows[-1]), file=sys.stderr)
    print("| mesh | split | hexes | tets | qmesh #Q | #h | #t | MB | s | HXT #Q | #h | #t | MB | s | time ratio | memory ratio |")
    print("|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|")
    for r in rows:
        print(
            f"| {r['mesh']} | {r['split']} | {r['hexes_in']:,} | {r['tets']:,} | {r['q_Q']:,} | {r['q_h']:,} | {r['q_t']:,} "
            f"| {r['q_mb']:.0f} | {r['q_s']:.2f} | {r['h_Q']:,} | {r['h_h']:,} | {r['h_t']:,} | {r['h_mb']:.0f} "
            f"| {r['h_s']:.2f} | {r['q_s'] / r['h_s']:.2f} | {r['q_mb'] / r['h_mb']:.2f} |"
        )


main()
