#!/usr/bin/env python3
"""A two-storey building made of volumes, for 2025 §7.2 (batch edit of repeated parts):
slabs, walls cut into pieces wherever another wall, a door or a window meets them,
glass panes, doors (one polyhedron each, doors of several widths) and, on both sides
of every door, the same lever handle of five volumes. Doors face four directions and
hinge on either side, so the handle appears in several orientations.

    python3 building.py OUT_DIR            # the model and the expected result
    python3 building.py --rule-meshes DIR  # the rule meshes m1, m2, m3

The model and the expected result:
  building.vtk           the model (cell array `label`: 1 slab, 2 wall, 3 glass, 4 door, 5 handle)
  building_expected.vtk  the building as a modeler would have drawn it with the new
                         handles, to check `qmesh modify` against.
The rule meshes (committed beside the rule file; open them in a modeler to change the
new handle, the rule file stays the same):
  m1.mesh, m2.mesh, m3.mesh   the rule meshes: the handle as found on a door (M1),
                         without the end of its lever (M2), with a new, longer lever (M3);
                         the face of M1/M2/M3 that lies on the door has reference 1.
Edit the dimensions below, or the new lever in NEW_LEVER, and rerun."""
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from meshfiles import Points, hexahedron, outward, run_generator, write_medit_hexahedra, write_polyhedra  # noqa: E402

SLAB, WALL, GLASS, DOOR, HANDLE = 1, 2, 3, 4, 5
WIDTH, DEPTH = 12.0, 8.0          # footprint along x and y
THICK = LEAF = 0.3                # wall thickness; doors and glass fill it
LEVELS = [(0.0, 0.3), (3.0, 3.3), (6.0, 6.3)]   # slabs: ground, first floor, roof
STOREYS = [(0.3, 3.0), (3.3, 6.0)]
OPENING = 2.1                     # height of doors and French windows
X_WALLS = [0.0, 3.85, 7.7]        # walls along x: their lowest y
Y_WALLS = [0.0, 3.85, 7.85, 11.7]  # walls along y: their lowest x
# Openings: (wall direction, wall index, start along the wall, width, storey, kind, hinge).
OPENINGS = [
    ("x", 0, 5.5, 1.0, 0, "door", 0), ("x", 0, 1.2, 1.4, 0, "window", 0),
    ("x", 0, 9.4, 1.4, 0, "window", 0), ("x", 1, 1.6, 0.9, 0, "door", 1),
    ("x", 1, 9.9, 0.8, 0, "door", 0), ("x", 2, 2.9, 0.8, 0, "door", 1),
    ("x", 2, 5.0, 2.0, 0, "window", 0), ("y", 1, 1.5, 0.9, 0, "door", 0),
    ("y", 2, 5.4, 0.8, 0, "door", 1), ("y", 3, 5.4, 0.8, 0, "door", 0),
    ("y", 0, 1.0, 2.0, 0, "window", 0), ("y", 3, 1.0, 2.0, 0, "window", 0),
    ("x", 0, 1.2, 1.4, 1, "window", 0), ("x", 0, 5.0, 2.0, 1, "window", 0),
    ("x", 0, 9.4, 1.4, 1, "window", 0), ("x", 1, 1.6, 0.9, 1, "door", 0),
    ("x", 1, 9.9, 0.8, 1, "door", 1), ("x", 2, 5.0, 2.0, 1, "window", 0),
    ("y", 1, 5.4, 0.8, 1, "door", 1), ("y", 2, 1.5, 0.9, 1, "door", 0),
    ("y", 0, 5.0, 2.0, 1, "window", 0), ("y", 3, 1.0, 2.0, 1, "window", 0),
]
HANDLE_HEIGHT, HANDLE_INSET = 1.05, 0.1   # above the floor; from the lock edge

# The handle in its own frame: u along the lever (from the lock edge toward the hinge),
# v up, n out of the door face. Boxes are (u0, u1, v0, v1, n0, n1); the rosette is a
# frustum from the door face to the neck.
ROSETTE_BACK, ROSETTE_FRONT = (0.035, 0.09), (0.02, 0.02)   # half sizes (u, v)
NECK = [(-0.02, 0.02, -0.02, 0.02, 0.012, 0.04), (-0.02, 0.02, -0.02, 0.02, 0.04, 0.065)]
LEVER = [(0.02, 0.08, -0.02, 0.02, 0.04, 0.065)]             # kept by the delete
OLD_END = [(0.08, 0.13, -0.02, 0.02, 0.04, 0.065)]           # removed by the delete
# The new lever (added by the extend): a grip widening away from the neck, then a tip.
NEW_LEVER = [((0.08, 0.17), ((-0.02, 0.02, 0.04, 0.065), (-0.03, 0.03, 0.033, 0.072))),
             ((0.17, 0.2), ((-0.03, 0.03, 0.033, 0.072), (-0.018, 0.018, 0.042, 0.063)))]


def box(u0, u1, v0, v1, n0, n1):
    return tapered((u0, u1), (v0, v1, n0, n1), (v0, v1, n0, n1))


def tapered(us, near, far):
    """A hexahedron from the section `near` = (v0, v1, n0, n1) at u = us[0] to `far`
    at u = us[1], corners in the handle frame."""
    def section(u, s):
        v0, v1, n0, n1 = s
        return [(u, v0, n0), (u, v1, n0), (u, v1, n1), (u, v0, n1)]
    return section(us[0], near) + section(us[1], far)


def rosette():
    (bu, bv), (fu, fv) = ROSETTE_BACK, ROSETTE_FRONT
    n = NECK[0][4]
    return [(-bu, -bv, 0), (bu, -bv, 0), (bu, bv, 0), (-bu, bv, 0),
            (-fu, -fv, n), (fu, -fv, n), (fu, fv, n), (-fu, fv, n)]


def handle_parts(new):
    """Corner lists of the handle's volumes: M1's five, or M3's six when `new`."""
    parts = [rosette()] + [box(*b) for b in NECK + LEVER]
    if new:
        parts += [tapered(us, a, b) for us, (a, b) in NEW_LEVER]
    else:
        parts += [box(*b) for b in OLD_END]
    return parts


def grid_lines(along):
    """Coordinates of the grid lines along x (`along` = "x") or y."""
    walls, length = (Y_WALLS, WIDTH) if along == "x" else (X_WALLS, DEPTH)
    lines = {0.0, length}
    for w in walls:
        mid = w + THICK / 2
        lines |= {w, w + THICK, mid - LEAF / 2, mid + LEAF / 2}
    for o in OPENINGS:
        if o[0] == along:
            lines |= {o[2], o[2] + o[3]}
    return sorted(lines)


def in_wall(walls, c):
    return next((i for i, w in enumerate(walls) if w < c < w + THICK), None)


def main(out_dir):
    xs, ys = grid_lines("x"), grid_lines("y")
    zs = sorted({z for lv in LEVELS for z in lv} | {s[0] + OPENING for s in STOREYS})
    for o in OPENINGS:  # a door is one cell: no grid line may cut it
        lines = xs if o[0] == "x" else ys
        bad = [c for c in lines if o[2] < c < o[2] + o[3]]
        assert o[5] != "door" or not bad, f"door {o} is cut by grid lines {bad}"
    mesh = Model()
    for i in range(len(xs) - 1):
        for j in range(len(ys) - 1):
            for k in range(len(zs) - 1):
                cell = (xs[i], xs[i + 1], ys[j], ys[j + 1], zs[k], zs[k + 1])
                mesh.add_grid_cell(cell)
    write_model(out_dir, mesh)


class Model:
    """The building's volumes: each grid cell classified by its centre, doors as
    polyhedra carrying their handles."""

    def __init__(self):
        self.points, self.cells, self.labels = Points(), [], []
        self.expected_points, self.expected_cells, self.expected_labels = Points(), [], []
        self.doors = 0

    def add(self, label, corners=None, faces_of=None):
        for pts, cells, labels in ((self.points, self.cells, self.labels),
                                   (self.expected_points, self.expected_cells, self.expected_labels)):
            cells.append(hexahedron(pts, corners) if corners else faces_of(pts))
            labels.append(label)

    def add_grid_cell(self, cell):
        x0, x1, y0, y1, z0, z1 = cell
        c = ((x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2)
        corners = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
                   (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
        if any(a < c[2] < b for a, b in LEVELS):
            return self.add(SLAB, corners)
        storey = next(s for s, (a, b) in enumerate(STOREYS) if a < c[2] < b)
        wx, wy = in_wall(X_WALLS, c[1]), in_wall(Y_WALLS, c[0])
        if wx is None and wy is None:
            return  # a room
        for o in OPENINGS:
            wall, along, across = (wx, c[0], c[1]) if o[0] == "x" else (wy, c[1], c[0])
            walls = X_WALLS if o[0] == "x" else Y_WALLS
            if wall != o[1] or o[4] != storey or not o[2] < along < o[2] + o[3]:
                continue
            if c[2] > STOREYS[storey][0] + OPENING:
                break  # the lintel above the opening is wall
            mid = walls[wall] + THICK / 2
            if abs(across - mid) > LEAF / 2:
                return  # in front of or behind the leaf: air
            if o[5] == "window":
                return self.add(GLASS, corners)
            return self.add_door(o, cell)
        self.add(WALL, corners)

    def add_door(self, o, cell):
        """A door leaf whose two faces each carry a handle: the leaf is one polyhedron
        whose faces are split into the handle's footprint and a ring of four quads."""
        x0, x1, y0, y1, z0, z1 = cell
        if o[0] == "x":   # door frame: u along the wall, v up, n across
            origin, eu, en = (x0, (y0 + y1) / 2, z0), (1, 0, 0), (0, 1, 0)
        else:
            origin, eu, en = ((x0 + x1) / 2, y0, z0), (0, 1, 0), (1, 0, 0)
        width, height = o[3], z1 - z0
        lock = width - HANDLE_INSET if o[6] == 0 else HANDLE_INSET
        toward_hinge = -1 if o[6] == 0 else 1

        def world(u, v, n):
            return tuple(origin[i] + u * eu[i] + n * en[i] + (v if i == 2 else 0) for i in range(3))

        def handle_to_world(side):
            # handle frame (lever u, up v, out n) on the face n = side·LEAF/2
            return lambda p: world(lock + toward_hinge * p[0], HANDLE_HEIGHT + p[1],
                                   side * (LEAF / 2 + p[2]))

        self.doors += 1
        corners_uv = [(0, 0), (width, 0), (width, height), (0, height)]

        def door_faces(points):
            faces = []
            for side in (1, -1):
                at = handle_to_world(side)
                inner = [points.id(at(p)) for p in rosette()[:4]]
                # the leaf corner nearest each footprint corner, in the same turn
                outer = []
                for p in rosette()[:4]:
                    u, v = lock + toward_hinge * p[0], HANDLE_HEIGHT + p[1]
                    cu = 0 if u < lock else width
                    cv = 0 if v < HANDLE_HEIGHT else height
                    outer.append(points.id(world(cu, cv, side * LEAF / 2)))
                faces.append(inner)
                faces += [[inner[a], outer[a], outer[(a + 1) % 4], inner[(a + 1) % 4]] for a in range(4)]
            front = [points.id(world(u, v, LEAF / 2)) for u, v in corners_uv]
            back = [points.id(world(u, v, -LEAF / 2)) for u, v in corners_uv]
            faces += [[front[a], front[(a + 1) % 4], back[(a + 1) % 4], back[a]] for a in range(4)]
            return orient_leaf(points, faces)

        self.add(DOOR, faces_of=door_faces)
        for side in (1, -1):
            at = handle_to_world(side)
            for new, (pts, cells, labels) in ((False, (self.points, self.cells, self.labels)),
                                              (True, (self.expected_points, self.expected_cells,
                                                      self.expected_labels))):
                for part in handle_parts(new):
                    cells.append(hexahedron(pts, [at(p) for p in part]))
                    labels.append(HANDLE)


def orient_leaf(points, faces):
    """The leaf's faces, each turned to face out of the leaf (the ring quads and the
    footprints come in either turn), then the whole set oriented outward."""
    centre = [sum(points.coords[v][i] for f in faces for v in f) / sum(len(f) for f in faces) for i in range(3)]
    fixed = []
    for f in faces:
        p = [points.coords[v] for v in f]
        normal = [0.0, 0.0, 0.0]
        for a, b in zip(p, p[1:] + p[:1]):
            normal[0] += (a[1] - b[1]) * (a[2] + b[2])
            normal[1] += (a[2] - b[2]) * (a[0] + b[0])
            normal[2] += (a[0] - b[0]) * (a[1] + b[1])
        mid = [sum(q[i] for q in p) / len(p) for i in range(3)]
        out = sum(normal[i] * (mid[i] - centre[i]) for i in range(3))
        fixed.append(f if out > 0 else f[::-1])
    return outward(points, fixed)


def write_rule_meshes(out_dir):
    """M1, M2, M3 in the handle frame (the door face is n = 0), as Medit files."""
    parts = handle_parts(False)
    for name, volumes in (("m1", parts), ("m2", parts[:4]), ("m3", handle_parts(True))):
        write_medit_hexahedra(os.path.join(out_dir, f"{name}.mesh"), volumes, [(rosette()[:4], 1)])


def write_model(out_dir, mesh):
    os.makedirs(out_dir, exist_ok=True)
    write_polyhedra(os.path.join(out_dir, "building.vtk"), "a building with doors and handles (qmesh examples/building)",
                    mesh.points.coords, mesh.cells, mesh.labels)
    write_polyhedra(os.path.join(out_dir, "building_expected.vtk"),
                    "the building with the new handles, drawn directly (qmesh examples/building)",
                    mesh.expected_points.coords, mesh.expected_cells, mesh.expected_labels)
    print(f"{len(mesh.cells)} volumes, {mesh.doors} doors, {2 * mesh.doors} handles; "
          f"{len(mesh.points.coords)} points")


if __name__ == "__main__":
    run_generator("building.py OUT_DIR | building.py --rule-meshes DIR", write_rule_meshes, main)
