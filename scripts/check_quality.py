#!/usr/bin/env python3
"""Check `qmesh quality` against VTK's vtkMeshQuality (Verdict) on every hex and tet file.

usage: scripts/check_quality.py [DATA_DIR]   (needs `pip install vtk`; exit 1 on mismatch)
Each file is converted by qmesh to legacy VTK (so both tools see the same cells in the
same order), then every cell's scaled Jacobian is compared to 1e-9 relative."""
import json
import os
import pathlib
import subprocess
import sys
import tempfile

import vtk
from vtk.util.numpy_support import vtk_to_numpy

root = pathlib.Path(__file__).resolve().parent.parent
data = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else root.parent / "shared" / "data")
# $QMESH_BIN (CI: the test build) or the release binary.
qmesh = pathlib.Path(os.environ["QMESH_BIN"]) if "QMESH_BIN" in os.environ else root / "target" / "release" / "qmesh"
subprocess.run(["cargo", "build", "--release", "-q"], cwd=root, check=True)

worst, failures, files, cells = 0.0, [], 0, 0
with tempfile.TemporaryDirectory() as tmp:
    for f in sorted(list((data / "hex").iterdir()) + list((data / "tet").iterdir())):
        if f.suffix not in (".vtk", ".mesh", ".msh"):
            continue
        out = pathlib.Path(tmp) / "cells.vtk"
        subprocess.run([qmesh, "convert", f, out], check=True, capture_output=True)
        q = json.loads(subprocess.run([qmesh, "quality", out, "--json", "--per-cell"], check=True,
                                      capture_output=True, text=True).stdout)["per_cell"]
        reader = vtk.vtkUnstructuredGridReader()
        reader.SetFileName(str(out))
        reader.Update()
        mq = vtk.vtkMeshQuality()
        mq.SetInputData(reader.GetOutput())
        mq.SetHexQualityMeasureToScaledJacobian()
        mq.SetTetQualityMeasureToScaledJacobian()
        mq.Update()
        v = vtk_to_numpy(mq.GetOutput().GetCellData().GetArray("Quality"))
        file_worst = 0.0
        grid = reader.GetOutput()
        for i, ours in enumerate(q):
            # Hexahedra and tetrahedra: qmesh's prism and pyramid values use their own
            # corner definition (see README), not Verdict's.
            if ours is None or grid.GetCellType(i) not in (vtk.VTK_HEXAHEDRON, vtk.VTK_TETRA):
                continue
            diff = abs(ours - v[i]) / max(1.0, abs(v[i]))
            file_worst = max(file_worst, diff)
            cells += 1
        files += 1
        worst = max(worst, file_worst)
        status = "ok" if file_worst <= 1e-9 else "MISMATCH"
        if status != "ok":
            failures.append(f.name)
        print(f"{status:8} {f.name:40} cells {len(q):7}  max relative difference {file_worst:.2e}")
print(f"{files} files, {cells} cells, worst relative difference {worst:.2e}, vtk {vtk.vtkVersion.GetVTKVersion()}")
sys.exit(1 if failures else 0)
