#!/usr/bin/env bash
# Worked examples of the 2025 query-modify engine (qmesh query / qmesh modify), with
# every mesh made here by qmesh or written below: delete, extend and replace rules on
# generated grids, counts before and after, and a picture of each result.
#   examples/query-modify/run.sh            (uses $QMESH_BIN, default target/release/qmesh, built if needed)
set -euo pipefail
cd "$(dirname "$0")"
. ../qmesh_bin.sh
mkdir -p out
cd out

# Inputs, queries and targets.
"$Q" generate grid --size 6,4,1 -o slab.vtk
"$Q" generate grid --size 2,1,1 -o pair.vtk
"$Q" generate grid --size 1 -o hex.vtk
"$Q" generate grid --size 2 -o block.vtk
# The unit cube's corners (Medit vertex lines) and its hexahedron, shared by the query
# and the target below.
cube_corners='0 0 0 0
1 0 0 0
1 1 0 0
0 1 0 0
0 0 1 0
1 0 1 0
1 1 1 0
0 1 1 0'
cube_cell='Hexahedra
1
1 2 3 4 5 6 7 8 0'
# A hexahedron whose top face (reference 1) must be on the boundary …
printf 'MeshVersionFormatted 2\nDimension 3\nVertices\n8\n%s\n%s\nQuadrilaterals\n1\n5 6 7 8 1\nEnd\n' \
  "$cube_corners" "$cube_cell" > hex_top.mesh
# … and the same with a pyramid roof on that face.
printf 'MeshVersionFormatted 2\nDimension 3\nVertices\n9\n%s\n0.5 0.5 1.6 0\n%s\nPyramids\n1\n5 6 7 8 9 0\nEnd\n' \
  "$cube_corners" "$cube_cell" > hex_roof.mesh
# Two hexahedra merged into one polyhedron with the pair's ten boundary quads.
cat > pair_merged.vtk <<'VTK'
# vtk DataFile Version 2.0
a 2x1x1 pair as one polyhedron
ASCII
DATASET UNSTRUCTURED_GRID
POINTS 12 double
0 0 0  1 0 0  2 0 0  0 1 0  1 1 0  2 1 0
0 0 1  1 0 1  2 0 1  0 1 1  1 1 1  2 1 1
CELLS 1 52
51 10 4 0 3 4 1 4 1 4 5 2 4 6 7 10 9 4 7 8 11 10 4 0 1 7 6 4 1 2 8 7 4 3 9 10 4 4 4 10 11 5 4 0 6 9 3 4 2 5 11 8
CELL_TYPES 1
42
VTK

cat > halve.toml <<'TOML'
# Delete: of every 2×1×1 pair of cells, keep the first (greedy, no overlaps).
[[rule]]
name = "halve"
op = "delete"
query = "pair.vtk"
target = "hex.vtk"
TOML
cat > roof.toml <<'TOML'
# Extend: a pyramid roof on every cell whose top face is on the boundary. The cube's
# automorphisms would put some roofs on the bottom or sides; "geometric" keeps, among
# them, the placement that fits the query's own orientation.
[[rule]]
name = "roof"
op = "extend"
query = "hex_top.mesh"
target = "hex_roof.mesh"
faces = { 1 = "eps" }
orientation = "geometric"
TOML
cat > merge.toml <<'TOML'
# Replace: every 2×1×1 pair of cells becomes one polyhedron (same boundary).
[[rule]]
name = "merge"
op = "replace"
query = "pair.vtk"
target = "pair_merged.vtk"
TOML
echo "== query: 2×2×2 blocks in the slab and in a 10³ grid"
"$Q" generate grid --size 10 -o grid10.vtk
"$Q" query block.vtk grid10.vtk -o grid10_blocks.vtk
for rules in halve roof merge; do
  echo "== modify: $rules.toml"
  "$Q" modify slab.vtk "slab_$rules.vtk" --rules "$rules.toml" --force
  "$Q" render "slab_$rules.vtk" -o "slab_$rules.png" --quiet >/dev/null
done
"$Q" render slab.vtk -o slab.png --quiet >/dev/null
echo "pictures: $(pwd)/slab.png and slab_{halve,roof,merge}.png"
