#!/usr/bin/env python3
"""Check that qmesh's VTK and VTU outputs open in VTK's own readers (what ParaView uses)
without warnings or errors, with the cell arrays qmesh promises.

usage: scripts/check_vtk_output.py [DATA_DIR]   (needs `pip install vtk`; exit 1 on failure)"""
import os
import pathlib
import subprocess
import sys
import tempfile

import vtk

root = pathlib.Path(__file__).resolve().parent.parent
data = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else root.parent / "shared" / "data")
# $QMESH_BIN (CI: the test build) or the release binary.
qmesh = pathlib.Path(os.environ["QMESH_BIN"]) if "QMESH_BIN" in os.environ else root / "target" / "release" / "qmesh"
subprocess.run(["cargo", "build", "--release", "-q"], cwd=root, check=True)

# Collect every warning and error VTK prints.
messages = []


class Catch(vtk.vtkOutputWindow):
    def DisplayText(self, text):
        messages.append(text)


catcher = Catch()
vtk.vtkOutputWindow.SetInstance(catcher)


def read(path):
    if path.suffix == ".vtu":
        r = vtk.vtkXMLUnstructuredGridReader()
    else:
        r = vtk.vtkUnstructuredGridReader()
        r.ReadAllScalarsOn()
    r.SetFileName(str(path))
    r.Update()
    out = r.GetOutput()
    cd = out.GetCellData()
    return out.GetNumberOfCells(), {cd.GetArrayName(i) for i in range(cd.GetNumberOfArrays())}


failures = []
with tempfile.TemporaryDirectory() as tmp:
    t = pathlib.Path(tmp)

    def q(*args):
        subprocess.run([qmesh, *map(str, args)], check=True, capture_output=True)

    q("subdivide", data / "surface" / "bunny.off", "--levels", "4", "-o", t / "octree.vtk", "-q")
    q("conformal", t / "octree.vtk", "-o", t / "conformal.vtu", "-q")
    q("convert", t / "conformal.vtu", t / "conformal_binary.vtk", "--binary")
    q("convert", data / "tet" / "hexme_s01u_cube.vtk", t / "labelled.vtu")
    q("tet2hex", data / "tet" / "CAD0.mesh", "-o", t / "tet2hex.vtk", "-q")
    expected = {
        "octree.vtk": {"cell_type", "scaled_jacobian", "level"},
        "conformal.vtu": {"cell_type", "scaled_jacobian", "pattern_id"},
        "conformal_binary.vtk": {"cell_type", "scaled_jacobian", "pattern_id"},
        "labelled.vtu": {"cell_type", "scaled_jacobian", "label"},
        "tet2hex.vtk": {"cell_type", "scaled_jacobian", "pattern_id"},
    }
    for name, arrays in expected.items():
        before = len(messages)
        cells, found = read(t / name)
        status = "ok"
        if cells == 0 or not arrays <= found or len(messages) > before:
            status = "FAIL"
            failures.append(name)
        print(f"{status:5} {name:22} cells {cells:7}  arrays {sorted(found)}  vtk messages {len(messages) - before}")
for m in messages:
    print("vtk:", m.strip())
print(f"vtk {vtk.vtkVersion.GetVTKVersion()}: {len(expected) - len(failures)}/{len(expected)} files read cleanly")
sys.exit(1 if failures else 0)
