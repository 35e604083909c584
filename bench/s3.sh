#!/usr/bin/env bash
# The 2022 paper's experiments on its own input S3 (cgal_mesh3.off, "Involute Blower"),
# l_max = 7, root cube on the longest bounding-box axis (margin 0), outside removed.
# usage: bench/s3.sh [OUTDIR]   (builds the release binary first)
set -euo pipefail
cd "$(dirname "$0")/.."
DATA=${QMESH_DATA:-$(cd .. && pwd)/shared/data}
OUT=${1:-/tmp/qmesh-s3}
mkdir -p "$OUT"
cargo build --release -q
Q=target/release/qmesh
S3="$DATA/surface/cgal_mesh3.off"
P325="$DATA/patterns/cgal/hexa-325-patterns,$DATA/patterns/cgal/square-5-patterns"
run() { echo "\$ qmesh $*"; /usr/bin/time -f "  wall %e s, peak %M KB" "$Q" "$@"; }
run subdivide "$S3" --levels 7 --margin 0 -o "$OUT/s3_all.vtk" -q
run subdivide "$S3" --levels 7 --margin 0 -o "$OUT/s3_all_direct.vtk" -q --direct
run subdivide "$S3" --levels 7 --margin 0 --remove-outside -o "$OUT/s3.vtk" -q
run subdivide "$S3" --levels 7 --margin 0 --remove-outside -o "$OUT/s3_direct.vtk" -q --direct
cmp "$OUT/s3.vtk" "$OUT/s3_direct.vtk" && echo "  query-replace and direct outputs are identical"
run conformal "$OUT/s3.vtk" -o "$OUT/s3_conformal_325.vtk" --patterns "$P325"
run conformal "$OUT/s3.vtk" -o "$OUT/s3_conformal_325_nosig.vtk" --patterns "$P325" --no-signatures
run conformal "$OUT/s3.vtk" -o "$OUT/s3_conformal_generated.vtk"
run marching-cubes "$S3" --levels 7 --margin 0.01 -o "$OUT/s3_mc.off" --triangulate
