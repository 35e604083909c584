"""The Python package as a mesh person uses it: files in and out, numpy arrays, the
reports with the CLI's keys, every application on small inputs, meshio and pyvista,
errors as exceptions, Ctrl-C."""
import json
import os
import pathlib
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import qmesh

ROOT = pathlib.Path(__file__).resolve().parents[3]
DATA = pathlib.Path(os.environ.get("QMESH_DATA", ROOT.parent / "shared" / "data"))


def data(rel):
    path = DATA / rel
    if not path.exists():
        if os.environ.get("QMESH_REQUIRE_DATA") == "1":
            pytest.fail(f"{path} is missing (QMESH_REQUIRE_DATA=1)")
        pytest.skip(f"{path} is missing (set QMESH_DATA to the shared data folder)")
    return path


def grid(n=2):
    """An n×n×n grid of unit hexahedra, from arrays."""
    idx = lambda i, j, k: i + (n + 1) * (j + (n + 1) * k)  # noqa: E731
    points = [(i, j, k) for k in range(n + 1) for j in range(n + 1) for i in range(n + 1)]
    hexes = [[idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k),
              idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1), idx(i, j + 1, k + 1)]
             for k in range(n) for j in range(n) for i in range(n)]
    return qmesh.from_arrays(np.array(points, float), {"hexahedron": np.array(hexes)})


def test_version_and_api():
    assert qmesh.__version__.count(".") == 2
    for name in ["read", "from_arrays", "marching_cubes", "from_meshio", "from_pyvista", "Mesh", "MeshError"]:
        assert hasattr(qmesh, name), name


def test_arrays_are_numpy_with_the_promised_shapes_and_no_copy():
    m = qmesh.read(data("hex/rockerarm.mesh"))
    p = m.points
    assert p.dtype == np.float64 and p.shape == (12751, 3)
    assert not p.flags.writeable, "points are a read-only view"
    assert np.shares_memory(p, m.points), "two reads of .points see the same memory: no copy"
    with pytest.raises(ValueError):
        p[0, 0] = 1.0
    hexes = m.cells["hexahedron"]
    assert hexes.dtype == np.int64 and hexes.shape == (10600, 8)
    assert hexes.min() >= 0 and hexes.max() < len(p)
    assert m.is_volume and m.polyhedra == []


def test_write_read_round_trip_keeps_cells_and_labels(tmp_path):
    g = grid(2)
    labels = np.array([1, 1, 2, 2, 3, 3, 4, 4], np.int32)
    g = qmesh.from_arrays(g.points, g.cells, cell_data={"label": {"hexahedron": labels}})
    for ext in ["vtk", "vtu", "mesh", "msh"]:
        path = tmp_path / f"g.{ext}"
        g.write(path)
        back = qmesh.read(path)
        assert np.allclose(back.points, g.points), ext
        assert np.array_equal(back.cells["hexahedron"], g.cells["hexahedron"]), ext
        assert np.array_equal(back.cell_data["label"]["hexahedron"], labels), ext
    # A volume mesh written to a surface format is its boundary, never an empty file.
    g.write(tmp_path / "g.off")
    surface = qmesh.read(tmp_path / "g.off")
    assert not surface.is_volume and len(surface.cells["quad"]) == 24


def test_reports_have_the_cli_keys():
    path = data("hex/rockerarm.mesh")
    m = qmesh.read(path)
    info, validity, quality = m.info(), m.validate(), m.quality(per_cell=True)
    assert (info["volumes"], info["cell_types"]["hex"], info["valid"]) == (10600, 10600, True)
    assert validity["valid"] and validity["geometrically_valid"] and validity["problems"] == []
    assert quality["scaled_jacobian"]["hex"]["count"] == 10600 and len(quality["per_cell"]) == 10600
    cli = os.environ.get("QMESH_BIN")
    if cli:  # the same keys as the command line's JSON (the process's memory aside)
        j = json.loads(subprocess.run([cli, "info", str(path), "--json"], capture_output=True, text=True,
                                      check=True).stdout)
        assert set(j) - {"peak_memory_bytes"} == set(info)
        assert {k: j[k] for k in ("darts", "vertices", "edges", "faces")} == {k: info[k] for k in
                                                                               ("darts", "vertices", "edges", "faces")}
        q = json.loads(subprocess.run([cli, "quality", str(path), "--json"], capture_output=True, text=True,
                                      check=True).stdout)
        assert q["scaled_jacobian"] == quality["scaled_jacobian"]


def test_marching_cubes_of_a_numpy_field_is_a_closed_sphere():
    n = 32
    x = np.linspace(-1, 1, n)
    field = np.sqrt(x[:, None, None] ** 2 + x[None, :, None] ** 2 + x[None, None, :] ** 2) - 0.7
    surface, report = qmesh.marching_cubes(field, spacing=(2 / (n - 1),) * 3, origin=(-1, -1, -1))
    assert report["unmatched_volumes"] == 0
    info = surface.info()
    assert (info["boundary_edges"], info["euler_characteristic"], info["components"]) == (0, 2, 1)
    r = np.linalg.norm(surface.points, axis=1)
    assert abs(r.mean() - 0.7) < 0.02 and "triangle" in surface.cells
    with pytest.raises(qmesh.MeshValueError):
        qmesh.marching_cubes(np.zeros((4, 4)))


def test_tetrahedralize_recombine_tet2hex_on_a_grid():
    g = grid(3)
    tets, split = g.tetrahedralize(seed=3)
    assert split["hexes"] == 27 and split["tets"] == len(tets.cells["tetra"])
    hexes, report = tets.recombine()
    assert report["recombine"]["hexes"] == 27 and report["recombine"]["tets_left"] == 0 and report["valid"]
    assert len(hexes.cells["hexahedron"]) == 27
    small, _ = grid(1).tetrahedralize(five=True)
    four, _ = small.tet2hex()
    assert len(four.cells["hexahedron"]) == 4 * 5 and four.validate()["valid"]
    with pytest.raises(qmesh.MeshValueError, match="no tetrahedra"):
        g.tet2hex()


def test_subdivide_a_surface():
    surface = qmesh.read(data("surface/cube.off"))
    octree, report = surface.subdivide(levels=3)
    assert report["volumes"] == len(octree.cells["hexahedron"]) and octree.validate()["valid"]
    assert "level" in octree.cell_data


def test_subdivide_with_the_authors_root():
    # The authors' program (cgal_hexa_subdivision -lmax 3) on the bunny: 254 cells.
    surface = qmesh.read(data("surface/bunny.off"))
    octree, report = surface.subdivide(levels=3, remove_outside=True, init=1)
    assert (report["volumes"], report["faces_replaced"], report["volumes_replaced"]) == (254, 234, 56)
    assert len(octree.cells["hexahedron"]) == 254
    with pytest.raises(qmesh.MeshValueError, match="init must be at least 1"):
        surface.subdivide(levels=1, init=0)


def test_subdivide_conformal_gives_the_authors_counts():
    # cgal_hexa_subdivision -lmax 6 -create-transitions on the bunny, with its 325 + 5
    # transition patterns: 25,792 hex, 1,498 prisms, 17,002 pyramids, 12,845 tets.
    surface = qmesh.read(data("surface/bunny.off"))
    patterns = [data("patterns/cgal/hexa-325-patterns"), data("patterns/cgal/square-5-patterns")]
    mesh, report = surface.subdivide(levels=6, remove_outside=True, init=1, conformal=True,
                                     transition_patterns=patterns)
    t = report["transitions"]
    kinds = t["cell_types"]
    assert (kinds["hex"], kinds["prism"], kinds["pyramid"], kinds["tet"]) == (25792, 1498, 17002, 12845)
    assert t["replace"]["volumes_replaced"] == 2718 and t["non_conformal_faces"] == 0
    assert sum(len(c) for c in mesh.cells.values()) == 25792 + 1498 + 17002 + 12845
    with pytest.raises(qmesh.MeshValueError, match="only go with conformal"):
        surface.subdivide(levels=1, transition_patterns=patterns)


def test_modify_runs_a_rule_file(tmp_path):
    boots = ROOT / "examples" / "boots"
    subprocess.run([sys.executable, str(boots / "boots.py"), str(tmp_path)], check=True, capture_output=True)
    figures = qmesh.read(tmp_path / "figures.vtk")
    edited, report = figures.modify(boots / "boots.toml")
    rule = report["rules"][0]
    assert (rule["matches"], rule["modified"], rule["automorphisms"], rule["valid"]) == (16, 16, 4, True)
    assert len(edited.cells["hexahedron"]) == 96


def test_query_and_query_apply_with_a_python_function(tmp_path):
    boots = ROOT / "examples" / "boots"
    subprocess.run([sys.executable, str(boots / "boots.py"), str(tmp_path)], check=True, capture_output=True)
    figures = qmesh.read(tmp_path / "figures.vtk")
    report, matches = figures.query(boots / "boots.toml")
    assert report["rules"][0]["matches"] == 16 and len(matches[0]) == 16
    assert all(m.dtype == np.int64 and len(m) == 2 for m in matches[0]), "a boot is two cells"
    labels = np.concatenate(list(figures.cell_data["label"].values()))
    assert set(labels[np.concatenate(matches[0])]) == {2}, "the matched cells are the boots (label 2)"
    seen = []

    def lift(points, cells):  # move every boot up by 10
        seen.append((points.shape, len(cells)))
        return points + [0.0, 0.0, 10.0]

    lifted, report = figures.query_apply(boots / "boots.toml", lift)
    assert report["rules"][0]["modified"] == 16 and report["valid"] and seen[0] == ((12, 3), 2)
    assert np.isclose(lifted.points[:, 2].max() - figures.points[:, 2].max(), 10.0, atol=2.0)

    def wrong(points, cells):
        return np.zeros((2, 3))

    with pytest.raises(ValueError, match="expected 12×3"):
        figures.query_apply(boots / "boots.toml", wrong)

    def failing(points, cells):
        raise RuntimeError("no thanks")

    with pytest.raises(RuntimeError, match="no thanks"):
        figures.query_apply(boots / "boots.toml", failing)


def test_replace_and_conformal():
    tets, _ = grid(2).tetrahedralize(five=True)
    hexes, report = tets.replace(data("patterns/cgal/tetra-to-hexa"), split_edges=2)
    assert len(hexes.cells["hexahedron"]) == 4 * len(tets.cells["tetra"]) and hexes.validate()["valid"]
    assert report["volumes_replaced"] == len(tets.cells["tetra"])
    octree, _ = qmesh.read(data("surface/cube.off")).subdivide(levels=3)
    conformal, report = octree.conformal()
    assert conformal.validate()["valid"] and conformal.info()["non_conformal_faces"] == 0
    with pytest.raises(qmesh.MeshValueError, match="no such pattern folder"):
        tets.replace("/nowhere")


def test_meshio_round_trip(tmp_path):
    meshio = pytest.importorskip("meshio")
    m = qmesh.read(data("tet/gmsh_sphere_tet.msh"))
    mm = m.to_meshio()
    assert isinstance(mm, meshio.Mesh) and mm.cells[0].type == "tetra"
    mm.write(tmp_path / "s.vtu")
    back = qmesh.from_meshio(meshio.read(tmp_path / "s.vtu"))
    assert np.allclose(back.points, m.points) and np.array_equal(back.cells["tetra"], m.cells["tetra"])
    # Polyhedra (a door of the building example) survive too.
    polys = qmesh.from_arrays(*_one_polyhedron())
    again = qmesh.from_meshio(polys.to_meshio())
    assert again.polyhedra == polys.polyhedra


def _one_polyhedron():
    points = np.array([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)], float)
    faces = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
    return points, {}, [faces]


def test_pyvista_round_trip():
    pv = pytest.importorskip("pyvista")
    m = qmesh.read(data("hex/rockerarm.mesh"))
    grid_ = m.to_pyvista()
    assert isinstance(grid_, pv.UnstructuredGrid) and grid_.n_cells == 10600
    back = qmesh.from_pyvista(grid_)
    assert np.array_equal(back.cells["hexahedron"], m.cells["hexahedron"])
    poly = qmesh.from_arrays(*_one_polyhedron())
    g = poly.to_pyvista()
    assert g.n_cells == 1 and g.celltypes[0] == 42
    assert qmesh.from_pyvista(g).info()["volumes"] == 1


def test_errors_are_exceptions_with_the_cli_messages(tmp_path):
    with pytest.raises(qmesh.MeshIOError) as e:
        qmesh.read(tmp_path / "missing.vtk")
    assert isinstance(e.value, OSError) and "missing.vtk" in str(e.value)
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\nnot a point\n3 0 1 2\n")
    with pytest.raises(qmesh.MeshValueError) as e:
        qmesh.read(bad)
    assert isinstance(e.value, ValueError) and "bad.off:" in str(e.value) and "line 5" in str(e.value)
    with pytest.raises(qmesh.MeshValueError, match="n×3"):
        qmesh.from_arrays(np.zeros((4, 2)), {})
    with pytest.raises(qmesh.MeshValueError, match="not a point index"):
        qmesh.from_arrays(np.zeros((4, 3)), {"tetra": np.array([[0, 1, 2, 9]])})
    rules = tmp_path / "rules.toml"
    rules.write_text('[[rule]]\nop = "extend"\nquery = "nowhere.vtk"\n')
    with pytest.raises(qmesh.MeshValueError, match="rules.toml:"):
        grid(1).modify(rules)
    with pytest.raises(qmesh.MeshValueError, match="unknown format"):
        grid(1).write(tmp_path / "x.vtk", format="nope")


def test_long_calls_release_the_gil_and_stop_on_ctrl_c():
    surface = qmesh.read(data("surface/armadillo.obj"))
    ticks = []
    stop = threading.Event()

    def tick():  # runs only while the call has released the GIL
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.01)

    t = threading.Thread(target=tick)
    t.start()
    start = time.perf_counter()
    surface.subdivide(levels=6)
    stop.set()
    t.join()
    took = time.perf_counter() - start
    assert len([x for x in ticks if x > start]) > took / 0.01 / 2, "the other thread ran during the call"
    timer = threading.Timer(0.2, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        surface.subdivide(levels=8)
    assert time.perf_counter() - start < 1.0, "Ctrl-C is honoured within a fraction of a second"
