"""Conversions to and from meshio and pyvista (imported only when used: neither is a
dependency of qmesh)."""
import warnings

import numpy as np

# VTK cell types of meshio's block names.
VTK_TYPES = {"tetra": 10, "pyramid": 14, "wedge": 13, "hexahedron": 12, "triangle": 5, "quad": 9}
VTK_POLYGON, VTK_POLYHEDRON = 7, 42
VOLUME_BLOCKS = {"tetra", "pyramid", "wedge", "hexahedron"}
# Cell arrays that are a cell's label, in the order qmesh's readers take them.
LABEL_NAMES = ["CellEntityIds", "gmsh:physical", "gmsh:geometrical", "medit:ref", "label", "labels", "MaterialIds"]


def _polyhedron_groups(polyhedra):
    """Indices of the polyhedra by number of distinct nodes (meshio's "polyhedronN")."""
    groups = {}
    for i, faces in enumerate(polyhedra):
        groups.setdefault(len({v for f in faces for v in f}), []).append(i)
    return groups


def to_meshio(mesh):
    import meshio

    blocks, taken = [], []  # taken: (qmesh block, indices in it or None for all)
    for name, data in mesh.cells.items():
        blocks.append(meshio.CellBlock(name, data))
        taken.append((name, None))
    polyhedra = mesh.polyhedra
    for n, members in _polyhedron_groups(polyhedra).items():
        blocks.append(meshio.CellBlock(f"polyhedron{n}", [[np.asarray(f) for f in polyhedra[i]] for i in members]))
        taken.append(("polyhedron", members))
    if mesh.polygons:
        warnings.warn(f"to_meshio: {len(mesh.polygons)} polygons with more than 4 corners left out", stacklevel=3)
    cell_data = {name: [per_block[b] if members is None else per_block[b][members] for b, members in taken]
                 for name, per_block in mesh.cell_data.items()}
    return meshio.Mesh(np.array(mesh.points), blocks, cell_data=cell_data)


def from_meshio(m):
    from . import Mesh

    kept = [(k, b) for k, b in enumerate(m.cells) if b.type in VOLUME_BLOCKS or b.type.startswith("polyhedron")]
    if not kept:  # a surface
        kept = [(k, b) for k, b in enumerate(m.cells) if b.type in ("triangle", "quad")]
    skipped = sorted({b.type for b in m.cells} - {b.type for _, b in kept})
    if skipped:
        warnings.warn(f"from_meshio: blocks {', '.join(skipped)} left out", stacklevel=3)
    cells, polyhedra, parts = {}, [], {}
    for k, b in kept:
        name = "polyhedron" if b.type.startswith("polyhedron") else b.type
        if name == "polyhedron":
            polyhedra += [[[int(v) for v in f] for f in cell] for cell in b.data]
        else:
            cells.setdefault(name, []).append(np.asarray(b.data))
        parts.setdefault(name, []).append(k)
    cells = {name: np.concatenate(arrays) for name, arrays in cells.items()}
    cell_data = {}
    label = next((n for n in LABEL_NAMES if n in m.cell_data), None)
    for name, per_block in m.cell_data.items():
        if any(np.asarray(per_block[k]).ndim != 1 for k, _ in kept):
            continue  # vectors and tensors are not per-cell scalars
        target = "label" if name == label else name
        cell_data[target] = {b: np.concatenate([np.asarray(per_block[k]) for k in ks]) for b, ks in parts.items()}
    return Mesh.from_arrays(m.points, cells, polyhedra or None, cell_data or None)


def to_pyvista(mesh):
    import pyvista as pv
    import vtk

    streams, types, order = [], [], []
    for name, data in mesh.cells.items():
        k = data.shape[1]
        streams.append(np.hstack([np.full((len(data), 1), k, dtype=np.int64), data]).ravel())
        types.append(np.full(len(data), VTK_TYPES[name], dtype=np.uint8))
        order.append((name, len(data)))
    grid = pv.UnstructuredGrid(np.concatenate(streams) if streams else np.zeros(0, np.int64),
                               np.concatenate(types) if types else np.zeros(0, np.uint8), np.array(mesh.points))
    for faces in mesh.polyhedra:
        ids = vtk.vtkIdList()
        for v in [len(faces)] + [x for f in faces for x in [len(f)] + list(f)]:
            ids.InsertNextId(int(v))
        grid.InsertNextCell(VTK_POLYHEDRON, ids)
    for corners in mesh.polygons:
        grid.InsertNextCell(VTK_POLYGON, len(corners), list(corners))
    blocks = [name for name, _ in order] + (["polyhedron"] if mesh.polyhedra else []) + (
        ["polygon"] if mesh.polygons else [])
    for name, per_block in mesh.cell_data.items():
        grid.cell_data[name] = np.concatenate([per_block[b] for b in blocks])
    return grid


def from_pyvista(grid):
    from . import Mesh

    if not hasattr(grid, "celltypes"):
        grid = grid.cast_to_unstructured_grid()
    names = {v: k for k, v in VTK_TYPES.items()}
    types = np.asarray(grid.celltypes)
    volume = bool(np.isin(types, [10, 12, 13, 14, VTK_POLYHEDRON]).any())
    wanted = [t for t in (10, 14, 13, 12) if (types == t).any()] if volume else [t for t in (5, 9) if (types == t).any()]
    # (not grid.cells_dict: it refuses grids with polyhedra)
    connectivity, offsets = np.asarray(grid.cell_connectivity), np.asarray(grid.cell_offsets if hasattr(grid, "cell_offsets") else grid.offset)
    members = {names[t]: np.flatnonzero(types == t) for t in wanted}
    cells = {}
    for name, idx in members.items():
        k = {"tetra": 4, "pyramid": 5, "wedge": 6, "hexahedron": 8, "triangle": 3, "quad": 4}[name]
        cells[name] = connectivity[offsets[idx][:, None] + np.arange(k)].astype(np.int64)
    polyhedra = []
    if volume and (types == VTK_POLYHEDRON).any():
        members["polyhedron"] = np.flatnonzero(types == VTK_POLYHEDRON)
        for i in members["polyhedron"]:
            polyhedra.append([list(map(int, f.point_ids)) for f in grid.get_cell(int(i)).faces])
    left = set(np.unique(types).tolist()) - set(wanted) - ({VTK_POLYHEDRON} if volume else set())
    if left:
        warnings.warn(f"from_pyvista: cells of VTK types {sorted(left)} left out", stacklevel=3)
    label = next((n for n in LABEL_NAMES if n in grid.cell_data), None)
    cell_data = {}
    for name in grid.cell_data.keys():
        values = np.asarray(grid.cell_data[name])
        if values.ndim == 1:
            cell_data["label" if name == label else name] = {b: values[idx] for b, idx in members.items()}
    return Mesh.from_arrays(grid.points, cells, polyhedra or None, cell_data or None)
