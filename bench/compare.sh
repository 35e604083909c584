#!/usr/bin/env bash
# Side-by-side: `qmesh info` vs a C++ program on CGAL's Linear_cell_complex (one
# make_hexahedron/make_tetrahedron per cell, sew3_same_facets, count_all_cells, is_valid)
# on armadillo_out.mesh and a generated 50³ hex grid. Installs what it needs.
# usage: bench/compare.sh [RUNS]   (prints a Markdown table for BENCHMARKS.md)
# Times are medians of RUNS whole-process runs, the commands taken round-robin; peak
# RSS is the largest seen (wait4). qmesh runs once with its default thread pool (2 on
# the CI machine) and once with RAYON_NUM_THREADS=1; the CGAL program is sequential.
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${1:-3}
DATA=${QMESH_DATA:-$(cd .. && pwd)/shared/data}
WORK=${TMPDIR:-/tmp}/qmesh-bench
mkdir -p "$WORK"
if [ ! -f /usr/include/CGAL/Linear_cell_complex_for_combinatorial_map.h ]; then
  echo "installing libcgal-dev…" >&2
  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libcgal-dev) >&2
fi
g++ -O3 -DNDEBUG -std=c++17 bench/cgal_info.cpp -o "$WORK/cgal_info" -lgmp -lmpfr
cargo build --release -q
Q=target/release/qmesh
$Q generate grid --size 50 -o "$WORK/grid50.vtk" >&2
echo "| input | tool | darts | volumes | valid | time (s) | peak RSS (MB) | time ratio CGAL/qmesh | memory ratio CGAL/qmesh |"
echo "|---|---|---|---|---|---|---|---|---|"
for input in "$DATA/hex/armadillo_out.mesh" "$WORK/grid50.vtk"; do
  python3 bench/measure.py "$RUNS" qmesh -- "$Q" info "$input" --json \
    --- "qmesh, 1 thread" -- env RAYON_NUM_THREADS=1 "$Q" info "$input" --json \
    --- cgal -- "$WORK/cgal_info" "$input" > "$WORK/r.jsonl"
  python3 - "$input" "$WORK/r.jsonl" <<'PY'
import json, os, sys
rows = [json.loads(l) for l in open(sys.argv[2])]
c = rows[-1]
name = os.path.basename(sys.argv[1])
for r in rows:
    o = r["output"]
    ratio = f"{c['seconds'] / r['seconds']:.2f} | {c['peak_rss_bytes'] / r['peak_rss_bytes']:.2f} |" if r is not c else " | |"
    print(f"| {name} | {r['label']} | {o['darts']} | {o['volumes']} | {o['valid']} | {r['seconds']:.3f} | "
          f"{r['peak_rss_bytes'] / 1e6:.1f} | {ratio}")
PY
done
