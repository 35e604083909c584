// The CGAL peer of `qmesh info`: read a Medit .mesh or legacy ASCII .vtk (hexahedra and
// tetrahedra), one make_hexahedron/make_tetrahedron per cell, sew3_same_facets(),
// count_all_cells(), is_valid(). Built and run by bench/compare.sh.
#include <CGAL/Linear_cell_complex_for_combinatorial_map.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

typedef CGAL::Linear_cell_complex_for_combinatorial_map<3> LCC;
typedef LCC::Point Point;

struct Mesh {
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> cells;  // VTK node order, 4 or 8 nodes
};

static bool read_medit(const char* path, Mesh& m) {
  std::ifstream in(path);
  std::string kw;
  while (in >> kw) {
    if (kw == "Vertices") {
      std::size_t n; in >> n; m.points.reserve(n);
      for (std::size_t i = 0; i < n; ++i) { double x, y, z; long r; in >> x >> y >> z >> r; m.points.emplace_back(x, y, z); }
    } else if (kw == "Hexahedra" || kw == "Tetrahedra") {
      std::size_t n, k = kw == "Hexahedra" ? 8 : 4; in >> n;
      for (std::size_t i = 0; i < n; ++i) {
        std::vector<std::size_t> c(k); for (auto& v : c) { in >> v; --v; }
        long r; in >> r; m.cells.push_back(c);
      }
    } else if (kw == "End") break;
  }
  return !m.cells.empty();
}

static bool read_vtk(const char* path, Mesh& m) {
  std::ifstream in(path);
  std::string kw;
  while (in >> kw) {
    if (kw == "POINTS") {
      std::size_t n; std::string t; in >> n >> t;
      for (std::size_t i = 0; i < n; ++i) { double x, y, z; in >> x >> y >> z; m.points.emplace_back(x, y, z); }
    } else if (kw == "CELLS") {
      std::size_t n, size; in >> n >> size;
      for (std::size_t i = 0; i < n; ++i) { std::size_t k; in >> k; std::vector<std::size_t> c(k); for (auto& v : c) in >> v; m.cells.push_back(c); }
    } else if (kw == "CELL_TYPES") break;
  }
  return !m.cells.empty();
}

int main(int argc, char** argv) {
  if (argc < 2) { std::cerr << "usage: cgal_info FILE.mesh|FILE.vtk\n"; return 2; }
  auto t0 = std::chrono::steady_clock::now();
  Mesh m;
  bool ok = std::strstr(argv[1], ".vtk") ? read_vtk(argv[1], m) : read_medit(argv[1], m);
  if (!ok) { std::cerr << "no cells read\n"; return 2; }
  auto t1 = std::chrono::steady_clock::now();
  LCC lcc;
  for (const auto& c : m.cells) {
    const auto& p = m.points;
    if (c.size() == 8)  // CGAL order: 0-1-2-3 base, 5 above 0, 6 above 1, 7 above 2, 4 above 3
      lcc.make_hexahedron(p[c[0]], p[c[1]], p[c[2]], p[c[3]], p[c[7]], p[c[4]], p[c[5]], p[c[6]]);
    else
      lcc.make_tetrahedron(p[c[0]], p[c[1]], p[c[2]], p[c[3]]);
  }
  lcc.sew3_same_facets();
  auto t2 = std::chrono::steady_clock::now();
  std::vector<unsigned int> cells = lcc.count_all_cells();
  bool valid = lcc.is_valid();
  auto t3 = std::chrono::steady_clock::now();
  auto s = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
  std::printf("{\"darts\": %zu, \"vertices\": %u, \"edges\": %u, \"faces\": %u, \"volumes\": %u, \"components\": %u, "
              "\"valid\": %s, \"read_seconds\": %.4f, \"build_seconds\": %.4f, \"count_validate_seconds\": %.4f}\n",
              (std::size_t)lcc.number_of_darts(), cells[0], cells[1], cells[2], cells[3], cells[4], valid ? "true" : "false",
              s(t0, t1), s(t1, t2), s(t2, t3));
  return 0;
}
