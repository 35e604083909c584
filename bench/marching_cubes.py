#!/usr/bin/env python3
"""Marching cubes of fields side by side (issue 16 item 2): `qmesh marching-cubes
--field` (query-replace, slab by slab) against VTK's vtkFlyingEdges3D and
vtkMarchingCubes and scikit-image's marching_cubes (PyPI `vtk`, `scikit-image`), on
gyroids of 128³ and 256³ points, the shared 32³ noise field and a 64³ one, round-robin.

Times: the extraction inside each process (qmesh's `seconds`: marching cubes from the
loaded field to the polygons; the peers' filter call) and the whole process's wall time.
Memory: the peak RSS (GNU time) less the floor of the same program doing nothing (for
qmesh `qmesh --version`; for the peers a run that imports the libraries and loads the
field, less the field), so both count the field once. Prints a Markdown table with the
goal ratios: qmesh/FlyingEdges time (goal ≤ 3) and memory/field size (goal ≤ 4).

usage: bench/marching_cubes.py [--runs N] [--out DIR] [--fields gyroid128,gyroid256,noise32,noise64]"""
import argparse
import json
import os
import statistics
import sys
import tempfile

import numpy as np

from common import DATA, Q, ROOT, sh, timed

PEER = os.path.join(ROOT, "bench", "mc_peer.py")
PEERS = ["flying-edges", "marching-cubes", "skimage"]


def gyroid(n):
    """The shared data's gyroid recipe (fields/README.md) at n points per axis."""
    x = np.linspace(0.0, 4.0 * np.pi, n)
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    f = np.sin(X) * np.cos(Y) + np.sin(Y) * np.cos(Z) + np.sin(Z) * np.cos(X) + 0.001
    return closed(f)


def noise(n):
    """Uniform values in [-1, 1] (seeded), as the shared 32³ noise field."""
    return closed(np.random.default_rng(1).uniform(-1.0, 1.0, (n, n, n)))


def closed(f):
    """The outer layer forced to +1, so that the surface is closed."""
    f[0, :, :] = f[-1, :, :] = f[:, 0, :] = f[:, -1, :] = f[:, :, 0] = f[:, :, -1] = 1.0
    return f.astype(np.float32)


def fields(names, out):
    """(name, path, n) of each field asked for, written to `out` unless shared."""
    made = []
    for name in names:
        if name == "noise32":
            made.append((name, os.path.join(DATA, "fields", "field_noise_32.f32"), 32))
            continue
        n = int(name.lstrip("gyroidnse"))
        path = os.path.join(out, f"{name}.f32")
        (gyroid(n) if name.startswith("gyroid") else noise(n)).tofile(path)
        made.append((name, path, n))
    return made


def run(cmd):
    """Wall seconds, peak RSS bytes and parsed JSON stdout of one run of cmd."""
    wall, rss, out = timed(cmd)
    return wall, rss, json.loads(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--out", default=None)
    ap.add_argument("--fields", default="gyroid128,gyroid256,noise32,noise64")
    a = ap.parse_args()
    out = a.out or tempfile.mkdtemp(prefix="qmesh-mc-")
    os.makedirs(out, exist_ok=True)
    sh("cargo", "build", "--release", "--quiet", cwd=ROOT)
    todo = fields(a.fields.split(","), out)
    commands = {}
    for name, path, n in todo:
        dims = f"{n},{n},{n}"
        commands[(name, "qmesh")] = [Q, "marching-cubes", "--field", path, "--dims", dims, "-o",
                                     os.path.join(out, f"{name}.off"), "--triangulate", "--force", "--json"]
        for tool in PEERS + ["load-vtk", "load-skimage"]:
            commands[(name, tool)] = [sys.executable, PEER, tool, path, str(n)]
    samples = {k: [] for k in commands}
    floors = []
    for _ in range(a.runs):
        floors.append(run_floor())
        for key, cmd in commands.items():
            samples[key].append(run(cmd))
    qmesh_floor = min(floors)
    print(f"qmesh process floor (`qmesh --version`): {qmesh_floor / 1e6:.1f} MB; {a.runs} runs, medians; "
          f"{os.cpu_count()} cores\n")
    print("| field | tool | triangles | extraction s | wall s | peak RSS MB | memory incl. field MB | ÷ field | time ÷ FlyingEdges |")
    print("|---|---|--:|--:|--:|--:|--:|--:|--:|")
    for name, path, n in todo:
        field_bytes = 4 * n ** 3
        floor_of = {t: max(s[1] for s in samples[(name, f"load-{lib}")]) - field_bytes
                    for t, lib in [("flying-edges", "vtk"), ("marching-cubes", "vtk"), ("skimage", "skimage")]}
        fe = statistics.median(s[2]["seconds"] for s in samples[(name, "flying-edges")])
        for tool in ["qmesh"] + PEERS:
            s = samples[(name, tool)]
            seconds = statistics.median(x[2]["seconds"] for x in s)
            wall = statistics.median(x[0] for x in s)
            peak = max(x[1] for x in s)
            memory = peak - (qmesh_floor if tool == "qmesh" else floor_of[tool])
            triangles = s[-1][2]["triangles"]
            print(f"| {name} ({field_bytes / 1e6:.1f} MB) | {tool} | {triangles:,} | {seconds:.3f} | {wall:.2f} | "
                  f"{peak / 1e6:.1f} | {memory / 1e6:.1f} | {memory / field_bytes:.2f} | {seconds / fe:.1f} |")


def run_floor():
    """Peak RSS of a qmesh process that does nothing."""
    return timed([Q, "--version"])[1]


if __name__ == "__main__":
    main()
