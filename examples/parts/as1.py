#!/usr/bin/env python3
"""The AS1 assembly (a plate, two L-brackets, a rod, six bolts, eight nuts; STEP file in
the shared data) as a surface model for 2025 §7.3: every part surface-meshed with gmsh
(PyPI) and written as one closed volume of the 3-map. Then the repeated parts are
sorted by the topology their meshes came out with (qmesh itself tells: a part whose
mesh matches another's as a query is the same class), and the rules that flange every
nut are written, one extend and one replace per class of nuts.

    python3 as1.py STEP OUT_DIR QMESH [--size H] [--algorithm A]
    python3 as1.py --check OUT_DIR RESULT.vtk

The first writes into OUT_DIR: as1.vtk (cell array `label`: 1 bolt, 2 l-bracket, 3 nut,
4 plate, 5 rod), flanges.toml and its meshes (nut_K.vtk, nut_K_flange.vtk,
nut_K_flanged.vtk for each class K), flange_options.json (each nut's flange drawn
directly on each of its two rings), and prints the classes as JSON. H is gmsh's
Mesh.MeshSizeMax (default 3), A its Mesh.Algorithm (default 6, Frontal-Delaunay).
The second says whether each nut of RESULT has one of its drawn flanges (to 0.01:
instances of one topology class differ slightly in shape, gmsh meshed each alone)."""
import json
import math
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, ".."))
sys.path.insert(0, here)
from flange import flanged  # noqa: E402
from meshfiles import write_polyhedra  # noqa: E402

KINDS = ["bolt", "l-bracket", "nut", "plate", "rod"]


def surface_model(step, size, algorithm):
    """Points, parts (outward triangle lists), kinds, and for each part the triangle
    indices of each of its planar faces with a hole (a nut's two rings)."""
    try:
        import gmsh
    except ImportError:
        sys.exit("as1.py needs gmsh: python3 -m pip install gmsh")
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.occ.importShapes(step)
    gmsh.model.occ.synchronize()
    gmsh.option.setNumber("Mesh.MeshSizeMax", size)
    gmsh.option.setNumber("Mesh.Algorithm", algorithm)
    gmsh.model.mesh.generate(2)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    index = {t: i for i, t in enumerate(tags)}
    points = [tuple(float(c) for c in coords[3 * i: 3 * i + 3]) for i in range(len(tags))]
    parts, kinds, rings = [], [], []
    for dim, volume in gmsh.model.getEntities(3):
        faces, holed_faces = [], []
        for _, s in gmsh.model.getBoundary([(dim, volume)], oriented=True):
            holed = gmsh.model.getType(2, abs(s)) == "Plane" and len(gmsh.model.getBoundary([(2, abs(s))])) > 4
            first = len(faces)
            for kind, nodes in zip(*gmsh.model.mesh.getElements(2, abs(s))[::2]):
                assert kind == 2, f"surface {abs(s)}: element type {kind}, expected triangles"
                for k in range(0, len(nodes), 3):
                    tri = [index[n] for n in nodes[k: k + 3]]
                    faces.append(tri if s > 0 else tri[::-1])
            if holed:
                holed_faces.append(list(range(first, len(faces))))
        name = gmsh.model.getEntityName(dim, volume).split("/")[-1].split(" ")[0]
        parts.append(faces)
        kinds.append(KINDS.index(name) + 1)
        rings.append(holed_faces)
    gmsh.finalize()
    return points, parts, kinds, rings


def alone(points, faces):
    """The part's own points and faces renumbered from 0."""
    used = sorted({v for f in faces for v in f})
    new = {v: i for i, v in enumerate(used)}
    return [points[v] for v in used], [[new[v] for v in f] for f in faces], new


def classes_of(qmesh, out, points, parts, ids):
    """Instances grouped by the topology of their meshes: instance i joins the first
    class whose representative, as a query, matches i's mesh."""
    classes = []
    for i in ids:
        path = os.path.join(out, f"part_{i}.vtk")
        coords, faces, _ = alone(points, parts[i])
        write_polyhedra(path, f"part {i} of as1", coords, [faces])
        for c in classes:
            query = os.path.join(out, f"part_{c[0]}.vtk")
            run = subprocess.run([qmesh, "query", query, path, "--boundary", "eps", "--json"],
                                 capture_output=True, text=True, check=True)
            if json.loads(run.stdout)["matches"] > 0:
                c.append(i)
                break
        else:
            classes.append([i])
    return classes


def check(out, result, tolerance):
    """Whether every nut of `result` has a flange within `tolerance` of the one drawn
    directly on one of its rings: prints a JSON summary, returns the exit status."""
    words = open(result).read().split()
    at = words.index("POINTS")
    pts = [tuple(float(w) for w in words[at + 3 + 3 * i: at + 6 + 3 * i]) for i in range(int(words[at + 1]))]
    options = json.load(open(os.path.join(out, "flange_options.json")))
    by_ring, worst = [0, 0], 0.0
    for choices in options:
        gaps = []
        for drawn in choices:
            near = max(min(math.dist(p, q) for q in pts) for p in drawn)
            gaps.append(near)
        k = min(range(len(gaps)), key=gaps.__getitem__)
        if gaps[k] <= tolerance:
            by_ring[k] += 1
            worst = max(worst, gaps[k])
    done = sum(by_ring)
    print(json.dumps({"nuts": len(options), "flanged_as_drawn": done, "on_first_ring": by_ring[0],
                      "on_second_ring": by_ring[1], "largest_gap": worst, "tolerance": tolerance}))
    return 0 if done == len(options) else 1


def main(step, out, qmesh, size=3.0, algorithm=6):
    os.makedirs(out, exist_ok=True)
    points, parts, kinds, rings = surface_model(step, size, algorithm)
    write_polyhedra(os.path.join(out, "as1.vtk"), "AS1 assembly, one closed surface per part (qmesh examples/parts)",
                    points, parts, kinds)
    report = {"mesh_size": size, "algorithm": algorithm, "parts": len(parts), "triangles": sum(map(len, parts))}
    classes = {}
    for kind in (1, 2, 3):
        ids = [i for i, k in enumerate(kinds) if k == kind]
        classes[kind] = classes_of(qmesh, out, points, parts, ids)
        report[KINDS[kind - 1]] = {"instances": len(ids), "classes": [len(c) for c in classes[kind]]}
    rules = ["# Written by as1.py: a flange on every nut of AS1, one extend and one replace per\n"
             "# class of nuts whose meshes have the same topology (see nuts.toml).\n"]
    for k, members in enumerate(classes[3]):
        coords, faces, new = alone(points, parts[members[0]])
        ring = rings[members[0]][0]
        write_polyhedra(os.path.join(out, f"nut_{k}.vtk"), "a nut of as1", coords, [faces])
        f_coords, extend_target, replace_target = flanged(coords, faces, ring)
        write_polyhedra(os.path.join(out, f"nut_{k}_flange.vtk"), "the nut with a flange", f_coords, extend_target)
        write_polyhedra(os.path.join(out, f"nut_{k}_flanged.vtk"), "the flanged nut", f_coords, replace_target)
        rules.append(f'\n[[rule]]\nname = "glue-flange-{k}"\nop = "extend"\nquery = "nut_{k}.vtk"\n'
                     f'target = "nut_{k}_flange.vtk"\nboundary = "eps"\norientation = "geometric"\n'
                     f'\n[[rule]]\nname = "merge-flange-{k}"\nop = "replace"\nquery = "nut_{k}_flange.vtk"\n'
                     f'target = "nut_{k}_flanged.vtk"\nboundary = "eps"\n')
    with open(os.path.join(out, "flanges.toml"), "w") as f:
        f.writelines(rules)
    # What a modeler would draw: each nut flanged from its own mesh, on either ring (a
    # nut is symmetric: which ring an edit takes is not decided by its shape).
    options = []
    for i, faces in enumerate(parts):
        if kinds[i] == 3:
            coords, local, _ = alone(points, faces)
            options.append([flanged(coords, local, ring)[0][len(coords):] for ring in rings[i]])
    with open(os.path.join(out, "flange_options.json"), "w") as f:
        json.dump(options, f)
    print(json.dumps(report))


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) == 3 and args[0] == "--check":
        sys.exit(check(args[1], args[2], 0.01))
    opts = {"--size": 3.0, "--algorithm": 6}
    while len(args) > 3 and args[-2] in opts:
        opts[args[-2]] = type(opts[args[-2]])(args[-1])
        args = args[:-2]
    if len(args) != 3:
        sys.exit("usage: as1.py STEP OUT_DIR QMESH [--size H] [--algorithm A]")
    main(*args, size=opts["--size"], algorithm=opts["--algorithm"])
