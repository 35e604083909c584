#!/usr/bin/env python3
"""The Python package's overhead (issue 13), round-robin in one run:
  1. `qmesh.read(f)` + `.info()` in a running interpreter, against the CLI's
     `qmesh info f` wall time (a process each), on armadillo_out.mesh;
  2. the same as whole processes: `python3 -c "import qmesh; ..."` against the CLI;
  3. `qmesh.marching_cubes` on a 128³ numpy field against skimage.measure.marching_cubes.

    python3 bench/python_overhead.py QMESH_BIN DATA_DIR [ROUNDS]"""
import statistics
import subprocess
import sys
import time

import numpy as np

import qmesh


def wall(cmd):
    t = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True)
    return time.perf_counter() - t


def main(cli, data, rounds=5):
    path = f"{data}/hex/armadillo_out.mesh"
    code = f"import qmesh; qmesh.read({path!r}).info()"
    times = {"cli": [], "call": [], "process": []}
    for _ in range(rounds):
        times["cli"].append(wall([cli, "info", path, "--json"]))
        t = time.perf_counter()
        qmesh.read(path).info()
        times["call"].append(time.perf_counter() - t)
        times["process"].append(wall([sys.executable, "-c", code]))
    med = {k: statistics.median(v) for k, v in times.items()}
    print(f"armadillo_out.mesh, median of {rounds}: CLI `qmesh info` {med['cli']:.3f} s; "
          f"qmesh.read + info() {med['call']:.3f} s ({med['call'] / med['cli']:.2f}× the CLI); "
          f"whole python process {med['process']:.3f} s ({med['process'] / med['cli']:.2f}×)")
    n = 128
    x = np.linspace(-np.pi, np.pi, n, dtype=np.float32)
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    field = np.sin(X) * np.cos(Y) + np.sin(Y) * np.cos(Z) + np.sin(Z) * np.cos(X)  # a gyroid
    try:
        from skimage.measure import marching_cubes as skimage_mc
    except ImportError:
        skimage_mc = None
    mc = {"qmesh": [], "skimage": []}
    for _ in range(min(rounds, 3)):
        t = time.perf_counter()
        surface, _ = qmesh.marching_cubes(field)
        mc["qmesh"].append(time.perf_counter() - t)
        if skimage_mc:
            t = time.perf_counter()
            verts, faces, _, _ = skimage_mc(field, 0.0)
            mc["skimage"].append(time.perf_counter() - t)
    line = f"gyroid 128³: qmesh.marching_cubes {statistics.median(mc['qmesh']):.2f} s, " \
           f"{len(surface.cells['triangle']):,} triangles"
    if skimage_mc:
        s = statistics.median(mc["skimage"])
        line += f"; skimage {s:.3f} s, {len(faces):,} triangles ({statistics.median(mc['qmesh']) / s:.0f}× slower)"
    print(line)


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit("usage: python_overhead.py QMESH_BIN DATA_DIR [ROUNDS]")
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 5)
