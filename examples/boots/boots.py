#!/usr/bin/env python3
"""Figures wearing boots, for 2025 §8 (Fig. 13b): a query with automorphisms. A boot
(a shaft on a foot whose sole reaches forward) is topologically two stacked
hexahedra: it matches in four ways, one per quarter turn about the leg. Adding a toe
cap to every boot must put it in front on every copy, whatever each copy's orientation
and however its cells were listed in the file.

    python3 boots.py OUT_DIR [COPIES] [SEED]    # the scene and the expected result
    python3 boots.py --rule-meshes DIR           # the rule meshes boot.mesh, boot_toe.mesh

The scene and the expected result:
  figures.vtk           COPIES figures (default 8), each turned by a random rotation
                        (seeded, default 1), each cell's faces in a random order and
                        each face starting at a random corner, as a modeler exports them
                        (cell array `label`: 1 body, 2 boot, 3 toe cap)
  figures_expected.vtk  the same figures with a toe cap on each boot, drawn directly.
The rule meshes: the left boot (the face under the thigh has reference 1) and the
same with its toe cap (reference 3: the label the new volumes get)."""
import os
import random
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from meshfiles import (Points, hexahedron, random_rotation, run_generator, shuffled,  # noqa: E402
                        write_medit_hexahedra, write_polyhedra)  # noqa: E402

BODY, BOOT, TOE = 1, 2, 3
SPACING = 4.5  # between the figures (each fits in a ball of radius 2 about its feet)


def block(x0, x1, y0, y1, z0, z1):
    return [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
            (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]


def frustum(bottom, z0, top, z1):
    """A hexahedron from the rectangle `bottom` = (x0, x1, y0, y1) at z0 to `top` at z1."""
    return block(*bottom, z0, z0)[:4] + block(*top, z1, z1)[4:]


def figure():
    """(label, corners) of one figure in its own frame: x right, y forward, z up."""
    torso = [block(x, x + 0.3, -0.15, 0.15, 1.0, 1.6) for x in (-0.45, -0.15, 0.15)]
    head = frustum((-0.15, 0.15, -0.15, 0.15), 1.6, (-0.1, 0.1, -0.06, 0.16), 1.9)
    cells = [(BODY, c) for c in torso + [head]]
    for dx in (0.0, 0.6):  # left leg, right leg
        cells.append((BODY, frustum((-0.45 + dx, -0.15 + dx, -0.15, 0.15), 1.0,
                                    (-0.4 + dx, -0.2 + dx, -0.1, 0.1), 0.55)))
        cells += [(BOOT, c) for c in boot(dx, toe=False)]
    return cells


def boot(dx, toe):
    """The boot under the leg shifted by `dx`: shaft, foot (sole reaching forward) and,
    with `toe`, the toe cap on the foot's front face."""
    shaft = frustum((-0.4 + dx, -0.2 + dx, -0.1, 0.1), 0.55, (-0.4 + dx, -0.2 + dx, -0.1, 0.1), 0.2)
    foot = frustum((-0.42 + dx, -0.18 + dx, -0.12, 0.22), 0.0, (-0.4 + dx, -0.2 + dx, -0.1, 0.1), 0.2)
    cells = [shaft[4:] + shaft[:4], foot]  # the shaft from its bottom up
    if toe:
        front = [foot[2], foot[3], foot[7], foot[6]]   # y = front of sole and top
        tip = [(-0.39 + dx, 0.34, 0.0), (-0.21 + dx, 0.34, 0.0), (-0.23 + dx, 0.3, 0.09), (-0.37 + dx, 0.3, 0.09)]
        tip = [tip[1], tip[0], tip[3], tip[2]]
        cells.append([front[0], front[1], tip[1], tip[0], front[3], front[2], tip[2], tip[3]])
    return cells


def scene(copies, seed, with_toes):
    turns, rng = random.Random(seed), random.Random(seed + 1)  # the same turns with or without toes
    points, cells, labels = Points(), [], []
    for c in range(copies):
        rot = random_rotation(turns)
        shift = (SPACING * (c % 4), SPACING * (c // 4), 0.0)

        def place(p, rot=rot, shift=shift):
            return tuple(sum(rot[i][j] * p[j] for j in range(3)) + shift[i] for i in range(3))

        parts = figure()
        if with_toes:
            parts += [(TOE, boot(dx, toe=True)[2]) for dx in (0.0, 0.6)]
        for label, corners in parts:
            cells.append(shuffled(hexahedron(points, [place(p) for p in corners]), rng))
            labels.append(label)
    order = list(range(len(cells)))
    rng.shuffle(order)
    return points.coords, [cells[i] for i in order], [labels[i] for i in order]


def write_rule_meshes(out_dir):
    top = boot(0.0, False)[0][4:]  # the shaft's face under the thigh
    for name, toe in (("boot", False), ("boot_toe", True)):
        hexes = boot(0.0, toe)
        refs = [TOE if k == 2 else 0 for k in range(len(hexes))]
        write_medit_hexahedra(os.path.join(out_dir, f"{name}.mesh"), hexes, [(top, 1)], refs)


def main(out_dir, copies, seed):
    os.makedirs(out_dir, exist_ok=True)
    for name, toes, title in (("figures", False, "figures in random orientations"),
                              ("figures_expected", True, "the figures with toe caps, drawn directly")):
        coords, cells, labels = scene(copies, seed, toes)
        write_polyhedra(os.path.join(out_dir, f"{name}.vtk"), f"{title} (qmesh examples/boots)",
                        coords, cells, labels)
    print(f"{copies} figures, {2 * copies} boots, {len(cells) - 2 * copies} volumes before the toe caps")


if __name__ == "__main__":
    run_generator("boots.py OUT_DIR [COPIES] [SEED] | boots.py --rule-meshes DIR", write_rule_meshes, main, (8, 1))
