#!/usr/bin/env python3
"""A synthetic model of repeated parts for 2025 §7.3 and §8 (Fig. 13a): hexagonal nuts
(a triangulated closed surface each, one volume of the 3-map) in random rigid poses,
each listed with its faces in a random order,
and round spacers that are look-alikes: the same mesh topology as a nut, another shape.
The rules give every nut a flange and must leave the spacers alone.

    python3 nuts.py OUT_DIR [NUTS] [SPACERS] [SEED]   # the model and the expected result
    python3 nuts.py --rule-meshes DIR                  # nut.vtk, nut_flange.vtk, nut_flanged.vtk

The model and the expected result:
  nuts.vtk            NUTS nuts (default 6) and SPACERS spacers (default 2), seeded
                      (default 1); cell array `label`: 1 nut, 2 spacer
  nuts_expected.vtk   the same with every nut flanged (one closed part each).
The rule meshes: a nut (the query of the extend), the nut with a flange glued on its
bottom ring (the extend's target and the replace's query) and the flanged nut as one
part (the replace's target)."""
import math
import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from flange import flanged  # noqa: E402
from meshfiles import Points, outward, random_rotation, run_generator, shuffled, write_polyhedra  # noqa: E402

NUT, SPACER = 1, 2
SIDES = 12            # vertices around the outside (hexagon corners and edge midpoints) and the hole
HOLE, HEIGHT, CHAMFER = 0.5, 0.8, 0.9   # hole radius, height (the nut's width across corners is 2)
SPACING = 4.0


def ring_part(outer, inner, height, top_scale):
    """A closed triangulated ring: the outline `outer` (SIDES points in the xy plane)
    around a hole of radius `inner`, extruded to `height`, its top outline scaled by
    `top_scale` (a chamfer). Returns (coords, faces, bottom ring faces)."""
    pts = Points()
    hole = [(inner * math.cos(2 * math.pi * k / SIDES), inner * math.sin(2 * math.pi * k / SIDES)) for k in range(SIDES)]
    ob = [pts.id((x, y, 0.0)) for x, y in outer]
    ot = [pts.id((top_scale * x, top_scale * y, height)) for x, y in outer]
    ib = [pts.id((x, y, 0.0)) for x, y in hole]
    it = [pts.id((x, y, height)) for x, y in hole]
    faces, bottom = [], []
    for k in range(SIDES):
        j = (k + 1) % SIDES
        bottom += [len(faces), len(faces) + 1]
        faces += [[ob[k], ib[j], ob[j]], [ob[k], ib[k], ib[j]]]       # bottom ring
        faces += [[ot[k], ot[j], it[j]], [ot[k], it[j], it[k]]]       # top ring
        faces += [[ob[k], ob[j], ot[j]], [ob[k], ot[j], ot[k]]]       # outside
        faces += [[ib[k], it[j], ib[j]], [ib[k], it[k], it[j]]]       # hole
    return pts.coords, outward(pts, faces), bottom


def nut():
    outline = []
    for k in range(SIDES):
        a = 2 * math.pi * k / SIDES
        r = 1.0 if k % 2 == 0 else math.cos(math.pi / 6)  # corners, then edge midpoints
        outline.append((r * math.cos(a), r * math.sin(a)))
    return ring_part(outline, HOLE, HEIGHT, CHAMFER)


def spacer():
    """Same topology as the nut; round, taller, no chamfer: not an affine copy of it."""
    outline = [(0.9 * math.cos(2 * math.pi * k / SIDES), 0.9 * math.sin(2 * math.pi * k / SIDES)) for k in range(SIDES)]
    return ring_part(outline, HOLE, 1.4, 1.0)


def model(nuts, spacers, seed, flanges):
    turns, rng = random.Random(seed), random.Random(seed + 1)  # the same poses with or without flanges
    pts, cells, labels = Points(), [], []
    coords, faces, bottom = nut()
    f_coords, _, (flanged_nut,) = flanged(coords, faces, bottom)
    kinds = [(NUT, f_coords, flanged_nut) if flanges else (NUT, coords, faces)] * nuts
    kinds += [(SPACER,) + spacer()[:2]] * spacers
    for c, (label, part_coords, part_faces) in enumerate(kinds):
        rot = random_rotation(turns)
        shift = (SPACING * (c % 4), SPACING * (c // 4), 0.0)
        place = [tuple(sum(rot[i][j] * p[j] for j in range(3)) + shift[i] for i in range(3)) for p in part_coords]
        used = sorted({v for f in part_faces for v in f})
        ids = {v: pts.id(place[v]) for v in used}
        cells.append(shuffled([[ids[v] for v in f] for f in part_faces], rng))
        labels.append(label)
    return pts.coords, cells, labels


def write_rule_meshes(out_dir):
    coords, faces, bottom = nut()
    write_polyhedra(os.path.join(out_dir, "nut.vtk"), "a nut (qmesh examples/parts)", coords, [faces])
    f_coords, extend_target, replace_target = flanged(coords, faces, bottom)
    write_polyhedra(os.path.join(out_dir, "nut_flange.vtk"), "a nut with a flange glued on (qmesh examples/parts)",
                    f_coords, extend_target)
    write_polyhedra(os.path.join(out_dir, "nut_flanged.vtk"), "a flanged nut (qmesh examples/parts)",
                    f_coords, replace_target)


def main(out_dir, nuts, spacers, seed):
    os.makedirs(out_dir, exist_ok=True)
    for name, flanges in (("nuts", False), ("nuts_expected", True)):
        coords, cells, labels = model(nuts, spacers, seed, flanges)
        write_polyhedra(os.path.join(out_dir, f"{name}.vtk"), f"{nuts} nuts and {spacers} spacers (qmesh examples/parts)",
                        coords, cells, labels)
    print(f"{nuts} nuts, {spacers} look-alike spacers")


if __name__ == "__main__":
    run_generator("nuts.py OUT_DIR [NUTS] [SPACERS] [SEED] | nuts.py --rule-meshes DIR", write_rule_meshes, main,
                  (6, 2, 1))
