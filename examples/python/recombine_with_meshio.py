#!/usr/bin/env python3
"""qmesh from Python, the way a notebook would use it: load a mesh with meshio, split
its hexahedra into tetrahedra and recombine them with qmesh (2025 §7.1), look at the
numbers, hand the result back to meshio and draw it with pyvista off-screen.

    python3 examples/python/recombine_with_meshio.py [HEX_MESH] [OUT_DIR]

(default: rockerarm.mesh of the shared data, out/ beside this script). Needs
`pip install ./crates/qmesh-py meshio pyvista`."""
import os
import pathlib
import sys

import meshio
import numpy as np

import qmesh

here = pathlib.Path(__file__).resolve().parent
data = pathlib.Path(os.environ.get("QMESH_DATA", here.parents[2] / "shared" / "data"))
source = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else data / "hex" / "rockerarm.mesh"
out = pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else here / "out"
out.mkdir(parents=True, exist_ok=True)

# 1. meshio reads, qmesh takes its arrays.
m = qmesh.from_meshio(meshio.read(source))
print(m, "| scaled Jacobian min", round(m.quality()["scaled_jacobian"]["hex"]["min"], 3))

# 2. Hexahedra → tetrahedra (every positive subdivision, seeded) → hexahedra again.
tets, split = m.tetrahedralize(seed=1)
print(f"tetrahedralize: {split['hexes']:,} hexahedra into {split['tets']:,} tetrahedra")
hexes, report = tets.recombine()
r = report["recombine"]
print(f"recombine: {r['queries']} queries, {r['matches']:,} matches, {r['hexes']:,} hexahedra, "
      f"{r['tets_left']:,} tetrahedra left, valid {report['valid']}; "
      f"query {r['query_seconds']:.2f} s, select {r['select_seconds']:.2f} s, replace {r['replace_seconds']:.2f} s")

# 3. numpy on the result: the recombined hexahedra's scaled Jacobians.
q = np.array([v for v in hexes.quality(per_cell=True)["per_cell"] if v is not None])
print(f"scaled Jacobian of the {q.size:,} recombined cells: min {q.min():.3f}, mean {q.mean():.3f}")

# 4. Back to meshio (any format it writes) and a picture with pyvista.
meshio.write(out / "recombined.vtu", hexes.to_meshio())
try:
    import pyvista as pv
    pv.OFF_SCREEN = True
    plotter = pv.Plotter(off_screen=True, window_size=(900, 700))
    plotter.add_mesh(hexes.to_pyvista().shrink(0.85), show_edges=True, color="tan")
    plotter.screenshot(out / "recombined.png")
    print(f"wrote {out / 'recombined.vtu'} and {out / 'recombined.png'}")
except Exception as e:  # no OpenGL context on this machine: the .vtu is there to open in ParaView
    print(f"wrote {out / 'recombined.vtu'} (no picture: pyvista could not render off-screen: {e})")
