#!/usr/bin/env bash
# Regenerates the rule meshes of this folder: the 3×3 block (flat top at the
# terrain's base height), the spot step 2 makes of it, and the house target.
#   examples/terrain/make_meshes.sh     (uses $QMESH_BIN, default target/release/qmesh)
set -euo pipefail
cd "$(dirname "$0")"
. ../qmesh_bin.sh
"$Q" generate terrain --size 3 --relief 0 --base 12 -o block.vtk -q
"$Q" modify block.vtk spot.vtk --rules flatten-one.toml --force -q
python3 house.py spot.vtk house.vtk
