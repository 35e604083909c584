#!/usr/bin/env bash
# Tetrahedra → hexahedra (2025 §7.1) on a shared hex mesh: split every hexahedron into
# tetrahedra (any positive subdivision), recombine them with the 330 subdivision rules,
# and draw the result by cell type and by scaled Jacobian; then recombine a real case,
# the gmsh tetrahedra of the HexMe sphere, and draw that too.
#   examples/recombine/run.sh [HEX_MESH]   (default: $QMESH_DATA/hex/rockerarm.mesh)
set -euo pipefail
cd "$(dirname "$0")"
. ../qmesh_bin.sh
data=${QMESH_DATA:-$root/../shared/data}
input=${1:-$data/hex/rockerarm.mesh}
mkdir -p out pictures
"$Q" tetrahedralize "$input" -o out/tets.mesh --any --seed 1 --force
"$Q" recombine out/tets.mesh -o out/recombined.vtk --force
"$Q" render out/recombined.vtk -o pictures/recombined_type.png --color-by type --clip "x<50%"
"$Q" render out/recombined.vtk -o pictures/recombined_quality.png --color-by quality --clip "x<50%"
"$Q" recombine "$data/tet/hexme_s17u_sphere.vtk" -o out/real.vtk --force
"$Q" render out/real.vtk -o pictures/real_type.png --color-by type --clip "x<50%"
"$Q" render out/real.vtk -o pictures/real_quality.png --color-by quality --clip "x<50%"
