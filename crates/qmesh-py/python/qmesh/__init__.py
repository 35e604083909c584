"""qmesh: topological rewriting of 3D meshes on combinatorial maps.

The 2022 query-replace applications (octree subdivision, marching cubes, tet → hex)
and the 2025 query-modify framework (rule files of extend / delete / replace / apply,
tetrahedra → hexahedra recombination), with numpy arrays in and out::

    import qmesh
    m = qmesh.read("part.mesh")
    m.points                        # n×3 float64, read-only view (no copy)
    m.cells["hexahedron"]           # m×8 int64
    m.info()["valid"]
    hexes, report = m.tetrahedralize(seed=1).recombine()
    hexes.write("part_hex.vtk")

Meshes never change: every operation returns a new one (and, where the command line
prints a report, a dict with its JSON keys). Long calls run without the GIL and stop
on Ctrl-C."""
import json as _json

import numpy as _np

from . import _qmesh
from .errors import MeshError, MeshIOError, MeshValueError

__version__ = _qmesh.__version__
__all__ = ["Mesh", "read", "from_arrays", "marching_cubes", "from_meshio", "from_pyvista",
           "MeshError", "MeshIOError", "MeshValueError", "__version__"]


class Mesh:
    """A volume mesh (cells) or a surface mesh (polygons), immutable."""

    __slots__ = ("_raw",)

    def __init__(self, raw):
        self._raw = raw

    # --- arrays -------------------------------------------------------------------

    @property
    def points(self):
        """n×3 float64 array of the point positions: a read-only view of the mesh's own
        memory (no copy; `np.array(m.points)` for a writable copy)."""
        return self._raw.points

    @property
    def cells(self):
        """{block: m×k int64 array} as meshio names them ("tetra", "pyramid", "wedge",
        "hexahedron"; "triangle", "quad" for surfaces), blocks in the order of their
        first cell. Polyhedra are in `polyhedra`, other polygons in `polygons`."""
        return self._raw.cells

    @property
    def polyhedra(self):
        """Every polyhedral cell as a list of faces (lists of point indices)."""
        return self._raw.polyhedra

    @property
    def polygons(self):
        """Polygons of a surface with other than 3 or 4 corners (lists of indices)."""
        return self._raw.polygons

    @property
    def cell_data(self):
        """{name: {block: array}}: `label` (Medit references, gmsh entities, VTK
        `CellEntityIds`) and the per-cell arrays qmesh writes (`level`, `pattern_id`,
        `scaled_jacobian`, …), split by block like `cells` (with "polyhedron")."""
        return self._raw.cell_data

    @property
    def is_volume(self):
        """True for a volume mesh, False for a surface."""
        return self._raw.is_volume

    def __repr__(self):
        blocks = ", ".join(f"{k}: {len(v)}" for k, v in self.cells.items())
        extra = f", polyhedron: {len(self.polyhedra)}" if self.polyhedra else ""
        return f"<qmesh.Mesh {len(self.points)} points; {blocks}{extra}>"

    @staticmethod
    def from_arrays(points, cells, polyhedra=None, cell_data=None):
        """A mesh from numpy arrays: `points` n×3, `cells` {block: m×k indices} (meshio
        names), `polyhedra` a list of cells each a list of faces, `cell_data` {name:
        {block: values}} (`label` becomes the cells' labels)."""
        cells = {k: _np.ascontiguousarray(v, dtype=_np.int64) for k, v in cells.items()}
        data = None
        if cell_data:
            data = {name: {k: _np.asarray(v) for k, v in blocks.items()} for name, blocks in cell_data.items()}
            for blocks in data.values():
                for k, v in blocks.items():
                    if v.dtype.kind in "iub":
                        blocks[k] = v.astype(_np.int32)
        raw = _qmesh.from_arrays(_np.ascontiguousarray(points, dtype=_np.float64), cells, polyhedra, data)
        return Mesh(raw)

    # --- files --------------------------------------------------------------------

    def write(self, path, binary=False, format=None):
        """Writes the mesh (format from the extension: vtk, vtu, mesh, msh, off, obj,
        stl, ply), atomically: a temporary file renamed into place. A volume mesh written
        to a surface format is its boundary surface."""
        self._raw.write(str(path), format, binary)

    # --- reports ------------------------------------------------------------------

    def info(self):
        """`qmesh info --json`: counts, cell types, conformity, geometric defects,
        validity, memory of the map and times."""
        return _json.loads(_qmesh.info(self._raw))

    def validate(self, max=20):
        """`qmesh validate --json`: `valid` (no combinatorial violation), the first
        `max` violations in `problems`, and the inverted, tangled and degenerate cells
        (`geometrically_valid`)."""
        return _json.loads(_qmesh.validate(self._raw, max))

    def quality(self, per_cell=False):
        """`qmesh quality --json`: scaled Jacobian (Verdict's definitions) per cell type
        and signed volumes; `per_cell` adds every cell's value."""
        return _json.loads(_qmesh.quality(self._raw, per_cell))

    # --- applications -------------------------------------------------------------

    def subdivide(self, levels=4, margin=0.01, remove_outside=False, direct=False, init=None,
                  conformal=False, transition_patterns=None):
        """The 2:1 octree of hexahedra around this surface, `levels` deep, by
        query-replace (2022 Algorithm 5). The root is one cube around the surface, or
        with `init` the bounding box in `init` cells along its longest axis (the
        authors' program's set-up). With `conformal`, the transitions (2022 Algorithm
        7) then run on the same map: hexahedra, prisms, pyramids and tetrahedra with no
        hanging vertex, with the `transition_patterns` folders or compiled sets (default:
        the generated set). Returns (mesh, report)."""
        patterns = None if transition_patterns is None else [str(p) for p in transition_patterns]
        return _pair(_qmesh.subdivide(self._raw, levels, margin, remove_outside, direct, init, conformal, patterns))

    def tet2hex(self):
        """Every tetrahedron into four hexahedra (2022 §7.4). Returns (mesh, report)."""
        return _pair(_qmesh.tet2hex(self._raw))

    def tetrahedralize(self, seed=0, five=False):
        """Every hexahedron split into tetrahedra without new points, conformally, all
        positive (2025 §7.1.1): drawn among all its subdivisions, or 5-tetrahedron
        splits where possible (`five`). Returns (mesh, report)."""
        return _pair(_qmesh.tetrahedralize(self._raw, seed, five))

    def recombine(self, strategy="best", min_quality=0.0, repair_effort=0.25, conformal=False):
        """Tetrahedra → hexahedra over every subdivision of the hexahedron (2025 §7.1).
        Returns (mesh, report)."""
        return _pair(_qmesh.recombine(self._raw, strategy, min_quality, repair_effort, conformal))

    def modify(self, rules):
        """Runs the rules of a rule file in order (`qmesh modify`): query, select,
        extend / delete / replace / apply. Returns (mesh, report with one entry per
        rule: matches, selected, modified, volumes and darts before and after, times,
        validity)."""
        return _pair(_qmesh.modify(self._raw, str(rules)))

    def query(self, rules):
        """The matches each rule of a rule file selects (its strategy, max, separation),
        without modifying: returns (report, matches) where matches[r] lists, for rule r,
        one int array of cell indices per selected match."""
        report, matches = _qmesh.query(self._raw, str(rules))
        return _json.loads(report), [[_np.asarray(m, dtype=_np.int64) for m in per_rule] for per_rule in matches]

    def query_apply(self, rules, function):
        """Query-apply (2025 §6.4) with a Python function: each match a rule selects is
        given to `function(points, cells)`, the k×3 positions of its vertices (in the
        order of the query's labels) and the indices of its cells; it returns new k×3
        positions, or None to leave the match as it is. Returns (mesh, report)."""
        return _pair(_qmesh.query_apply(self._raw, str(rules), function))

    def replace(self, patterns, split_edges=None, flags="corners"):
        """2022 query-replace with the f- and v-patterns of the folders (or files)
        `patterns`, after splitting every edge in `split_edges` when given; `flags`:
        corners (the papers' rule), geometric, file or none. Returns (mesh, report)."""
        if isinstance(patterns, (str, bytes)) or hasattr(patterns, "__fspath__"):
            patterns = [patterns]
        return _pair(_qmesh.replace(self._raw, [str(p) for p in patterns], split_edges, flags))

    def conformal(self, patterns=None):
        """Conformal 2:1 transitions (2022 Algorithm 7) of an octree mesh (as `subdivide`
        makes), with qmesh's generated transitions or the pattern folders `patterns`.
        Returns (mesh, report)."""
        return _pair(_qmesh.conformal(self._raw, None if patterns is None else [str(p) for p in patterns]))

    # --- other libraries ----------------------------------------------------------

    def to_meshio(self):
        """A `meshio.Mesh` with the same points, cell blocks (polyhedra as meshio's
        "polyhedron" blocks) and cell data."""
        from .interop import to_meshio
        return to_meshio(self)

    def to_pyvista(self):
        """A `pyvista.UnstructuredGrid` (polyhedra as VTK polyhedra) with the cell data."""
        from .interop import to_pyvista
        return to_pyvista(self)


def _pair(result):
    raw, report = result
    return Mesh(raw), _json.loads(report)


def read(path, format=None):
    """Reads a mesh: VTK (legacy, XML .vtu), gmsh .msh (2.2, 4.1), Medit .mesh, OFF,
    OBJ, STL, PLY, Moka. Raises MeshIOError (an OSError) when the file cannot be read,
    MeshValueError (a ValueError) naming the line when its content is wrong."""
    return Mesh(_qmesh.read(str(path), format))


def from_arrays(points, cells, polyhedra=None, cell_data=None):
    """As `Mesh.from_arrays`."""
    return Mesh.from_arrays(points, cells, polyhedra, cell_data)


def marching_cubes(field, iso=0.0, spacing=(1.0, 1.0, 1.0), origin=(0.0, 0.0, 0.0), triangles=True):
    """The surface where a 3D scalar field (a numpy array; inside where value ≤ iso)
    crosses `iso`, by query-replace of the marching-cubes patterns (2022 §7.2); point
    (i, j, k) of the grid is at origin + (i, j, k)·spacing. Returns (surface, report)."""
    field = _np.ascontiguousarray(field, dtype=_np.float32)
    if field.ndim != 3:
        raise MeshValueError(f"marching_cubes: expected a 3D array, got {field.ndim} dimensions")
    return _pair(_qmesh.marching_cubes(field, float(iso), tuple(map(float, spacing)), tuple(map(float, origin)),
                                       triangles))


def from_meshio(m):
    """A qmesh Mesh from a `meshio.Mesh`."""
    from .interop import from_meshio as convert
    return convert(m)


def from_pyvista(grid):
    """A qmesh Mesh from a `pyvista.UnstructuredGrid` (or anything with `cast_to_unstructured_grid`)."""
    from .interop import from_pyvista as convert
    return convert(grid)
