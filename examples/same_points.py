#!/usr/bin/env python3
"""Compares the points of two legacy ASCII VTK files as sets (to 1e-7): how many
points of RESULT are not in EXPECTED and the other way round. Prints one JSON line;
exits 1 when they differ. With --grid S, also the points of RESULT not in EXPECTED
counted per cell of an S×S grid in x, y (`extra_by_cell`, keyed "i,j"), to say which
copy of a repeated part differs.

    python3 same_points.py RESULT.vtk EXPECTED.vtk [--grid S]"""
import json
import sys


def points(path):
    words = open(path).read().split()
    at = words.index("POINTS")
    n = int(words[at + 1])
    return {tuple(round(float(w), 7) + 0.0 for w in words[at + 3 + 3 * i: at + 6 + 3 * i]) for i in range(n)}


if __name__ == "__main__":
    args = sys.argv[1:]
    grid = None
    if len(args) == 4 and args[2] == "--grid":
        grid = float(args[3])
        args = args[:2]
    if len(args) != 2:
        sys.exit("usage: same_points.py RESULT.vtk EXPECTED.vtk [--grid S]")
    result, expected = points(args[0]), points(args[1])
    report = {"result": len(result), "expected": len(expected),
              "extra": len(result - expected), "missing": len(expected - result)}
    if grid:
        cells = {}
        for p in sorted(result - expected):
            key = f"{round(p[0] / grid)},{round(p[1] / grid)}"
            cells[key] = cells.get(key, 0) + 1
        report["extra_by_cell"] = cells
    print(json.dumps(report))
    sys.exit(0 if result == expected else 1)
