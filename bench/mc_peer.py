#!/usr/bin/env python3
"""One marching-cubes run of a peer on a raw float32 field, for bench/marching_cubes.py:
prints {"seconds": extraction time in the process, "triangles": n}.

usage: bench/mc_peer.py (flying-edges | marching-cubes | skimage | load-vtk | load-skimage) FIELD N
`load-…` reads the field and imports the library but extracts nothing: the baseline
whose peak memory the library's filters are compared with. The field's index is (i·n + j)·n + k,
k fastest: VTK's x is our k, and scikit-image takes the array as (i, j, k)."""
import json
import sys
import time

import numpy as np


def main():
    tool, path, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
    values = np.fromfile(path, dtype=np.float32)
    if values.size != n ** 3:
        sys.exit(f"{path}: {values.size} values, {n ** 3} expected")
    if tool in ("flying-edges", "marching-cubes", "load-vtk"):
        import vtk
        from vtk.util import numpy_support
        image = vtk.vtkImageData()
        image.SetDimensions(n, n, n)
        image.GetPointData().SetScalars(numpy_support.numpy_to_vtk(values, deep=0))
    if tool in ("skimage", "load-skimage"):
        from skimage.measure import marching_cubes
        volume = values.reshape(n, n, n)
    if tool.startswith("load"):
        print(json.dumps({"seconds": 0.0, "triangles": 0}))
        return
    t = time.perf_counter()
    if tool == "skimage":
        _, faces, _, _ = marching_cubes(volume, level=0.0)
        triangles = len(faces)
    else:
        f = vtk.vtkFlyingEdges3D() if tool == "flying-edges" else vtk.vtkMarchingCubes()
        f.SetInputData(image)
        f.SetValue(0, 0.0)
        f.ComputeNormalsOff()
        f.ComputeGradientsOff()
        f.ComputeScalarsOff()
        f.Update()
        triangles = f.GetOutput().GetNumberOfCells()
    print(json.dumps({"seconds": time.perf_counter() - t, "triangles": triangles}))


if __name__ == "__main__":
    main()
