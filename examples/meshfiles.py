"""Small helpers shared by the example scripts (and their command line): volumes as lists of faces (each face a
list of point ids, counter-clockwise seen from outside), points merged by position so
that volumes touching along a face share it, legacy ASCII VTK files of polyhedra
(cell type 42, which qmesh, ParaView and meshio all read) and Medit files of
hexahedra with referenced quadrilaterals (how a rule's query names its faces)."""


import math
import sys


def run_generator(usage, write_rule_meshes, main, defaults=()):
    """The command line of the example generators: `--rule-meshes DIR`, or `OUT_DIR`
    and up to len(defaults) integers (the rest take their defaults)."""
    args = sys.argv[1:]
    if len(args) == 2 and args[0] == "--rule-meshes":
        write_rule_meshes(args[1])
    elif 1 <= len(args) <= 1 + len(defaults) and not args[0].startswith("-"):
        try:
            numbers = [int(a) for a in args[1:]]
        except ValueError:
            sys.exit("usage: " + usage)
        main(args[0], *numbers, *defaults[len(numbers):])
    else:
        sys.exit("usage: " + usage)


def random_rotation(rng):
    """A uniformly random rotation matrix (from a random unit quaternion)."""
    while True:
        q = [rng.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(x * x for x in q))
        if n > 1e-6:
            break
    w, x, y, z = (c / n for c in q)
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


class Points:
    """Point ids by position: the same position (to 1e-9) always gives the same id."""

    def __init__(self):
        self.coords = []
        self._ids = {}

    def id(self, p):
        key = tuple(round(c, 9) for c in p)
        if key not in self._ids:
            self._ids[key] = len(self.coords)
            self.coords.append(tuple(float(c) for c in p))
        return self._ids[key]


def hexahedron(points, corners):
    """The six faces of a hexahedron given by its 8 corners in VTK order (bottom quad,
    then the top quad above it), oriented outward whatever the corners' handedness."""
    v = [points.id(c) for c in corners]
    faces = [[v[0], v[3], v[2], v[1]], [v[4], v[5], v[6], v[7]], [v[0], v[1], v[5], v[4]],
             [v[1], v[2], v[6], v[5]], [v[2], v[3], v[7], v[6]], [v[3], v[0], v[4], v[7]]]
    return outward(points, faces)


def shuffled(cell, rng):
    """The faces of `cell` in a random order, each starting at a random corner."""
    faces = list(cell)
    rng.shuffle(faces)
    out = []
    for f in faces:
        k = rng.randrange(len(f))
        out.append(f[k:] + f[:k])
    return out


def signed_volume(points, faces):
    """The volume enclosed by `faces`, positive when they face outward."""
    total = 0.0
    for f in faces:
        a = points.coords[f[0]]
        for b_id, c_id in zip(f[1:], f[2:]):
            b, c = points.coords[b_id], points.coords[c_id]
            total += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                      + a[2] * (b[0] * c[1] - b[1] * c[0]))
    return total / 6.0


def outward(points, faces):
    """`faces`, reversed if they enclose a negative volume."""
    if signed_volume(points, faces) < 0:
        return [f[::-1] for f in faces]
    return faces


def read_polyhedra(path):
    """Points and cells (lists of faces) of a legacy ASCII VTK file of polyhedra, such
    as qmesh writes."""
    words = open(path).read().split()
    at = words.index("POINTS")
    n = int(words[at + 1])
    pts = [tuple(float(w) for w in words[at + 3 + 3 * i: at + 6 + 3 * i]) for i in range(n)]
    at = words.index("CELLS")
    ncells = int(words[at + 1])
    i = at + 3
    cells = []
    for _ in range(ncells):
        size = int(words[i])
        stream = [int(w) for w in words[i + 1: i + 1 + size]]
        i += 1 + size
        faces, k = [], 1
        for _ in range(stream[0]):
            m = stream[k]
            faces.append(stream[k + 1: k + 1 + m])
            k += 1 + m
        cells.append(faces)
    return pts, cells


def write_polyhedra(path, title, coords, cells, labels=None):
    """Writes `cells` (lists of faces over `coords`) as VTK polyhedra, with an integer
    cell array `label` when `labels` is given."""
    streams = []
    for faces in cells:
        s = [len(faces)]
        for f in faces:
            s += [len(f)] + list(f)
        streams.append(s)
    with open(path, "w") as out:
        out.write(f"# vtk DataFile Version 2.0\n{title}\nASCII\nDATASET UNSTRUCTURED_GRID\n")
        out.write(f"POINTS {len(coords)} double\n")
        for p in coords:
            out.write(" ".join(repr(round(float(c), 12)) for c in p) + "\n")
        out.write(f"CELLS {len(streams)} {sum(len(s) + 1 for s in streams)}\n")
        for s in streams:
            out.write(" ".join(str(x) for x in [len(s)] + s) + "\n")
        out.write(f"CELL_TYPES {len(streams)}\n" + "42\n" * len(streams))
        if labels is not None:
            out.write(f"CELL_DATA {len(cells)}\nSCALARS label int 1\nLOOKUP_TABLE default\n")
            out.write("\n".join(str(v) for v in labels) + "\n")


def write_medit_hexahedra(path, hexahedra, quads=(), hex_refs=None):
    """Writes hexahedra (each 8 corner positions in VTK order) as a Medit file, with the
    quadrilaterals `quads` (lists of 4 positions, with a reference each: (corners, ref))
    and a reference per hexahedron (`hex_refs`, default 0)."""
    pts = Points()
    hexes = [[pts.id(c) + 1 for c in h] for h in hexahedra]
    refs = hex_refs or [0] * len(hexes)
    with open(path, "w") as f:
        f.write("MeshVersionFormatted 2\nDimension 3\n")
        f.write(f"Vertices\n{len(pts.coords)}\n")
        f.writelines(" ".join(repr(round(float(c), 12)) for c in p) + " 0\n" for p in pts.coords)
        if quads:
            f.write(f"Quadrilaterals\n{len(quads)}\n")
            f.writelines(" ".join(str(pts.id(c) + 1) for c in q) + f" {r}\n" for q, r in quads)
        f.write(f"Hexahedra\n{len(hexes)}\n")
        f.writelines(" ".join(map(str, h)) + f" {r}\n" for h, r in zip(hexes, refs))
        f.write("End\n")
