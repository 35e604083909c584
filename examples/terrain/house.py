#!/usr/bin/env python3
"""Writes the target of the houses rule: the flattened spot (read from qmesh's output)
with a house of three volumes on its top face, a ground floor and an upper floor
(prisms on the spot's 12-sided top) and a roof whose triangulated top is an ellipse
around the ridge line.

    python3 house.py spot.vtk house.vtk

The spot is copied as it is, so the target contains the query exactly; open house.vtk
in ParaView or a modeler to change the house, the rule file stays the same."""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from meshfiles import read_polyhedra, write_polyhedra  # noqa: E402


def signed_area_xy(pts, ring):
    return sum(
        pts[a][0] * pts[b][1] - pts[b][0] * pts[a][1] for a, b in zip(ring, ring[1:] + ring[:1])
    ) / 2


def main(spot_path, out_path, wall=0.8, roof=1.0):
    pts, cells = read_polyhedra(spot_path)
    assert len(cells) == 1, f"{spot_path}: expected one volume (the flattened spot)"
    spot = cells[0]
    top = max(spot, key=len)
    assert len(top) == 12, f"{spot_path}: the spot's top should have 12 sides, found {len(top)}"
    ring0 = top if signed_area_xy(pts, top) > 0 else top[::-1]  # counter-clockwise from above
    pts = list(pts)
    cx = sum(pts[v][0] for v in ring0) / 12
    cy = sum(pts[v][1] for v in ring0) / 12
    z0 = pts[ring0[0]][2]

    def ring(f):
        ids = []
        for v in ring0:
            pts.append(f(pts[v]))
            ids.append(len(pts) - 1)
        return ids

    ring1 = ring(lambda p: (p[0], p[1], z0 + wall))
    ring2 = ring(lambda p: (p[0], p[1], z0 + 2 * wall))

    def on_ellipse(p):
        t = math.atan2(p[1] - cy, p[0] - cx)
        return (cx + 0.25 * math.cos(t), cy + 1.1 * math.sin(t), z0 + 2 * wall + roof)

    ring3 = ring(on_ellipse)

    def sides(lo, hi):
        return [[lo[k], lo[(k + 1) % 12], hi[(k + 1) % 12], hi[k]] for k in range(12)]

    floor1 = [ring0[::-1], ring1] + sides(ring0, ring1)
    floor2 = [ring1[::-1], ring2] + sides(ring1, ring2)
    fan = [[ring3[0], ring3[k], ring3[k + 1]] for k in range(1, 11)]
    roof_cell = [ring2[::-1]] + sides(ring2, ring3) + fan
    out = [spot, floor1, floor2, roof_cell]
    write_polyhedra(out_path, "flattened spot with a house (qmesh examples/terrain)", pts, out)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: house.py SPOT.vtk OUT.vtk")
    main(sys.argv[1], sys.argv[2])
