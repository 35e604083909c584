#!/usr/bin/env bash
# Reruns every comparison table of BENCHMARKS.md, one after the other (each script runs
# its peer in the same run, round-robin), and writes each table to OUTDIR/NAME.md.
# Takes about an hour on 2 cores; run it on a quiet machine.
# usage: bench/all.sh [OUTDIR] [RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-/tmp/qmesh-benchmarks}
RUNS=${2:-3}
DATA=${QMESH_DATA:-$(cd .. && pwd)/shared/data}
mkdir -p "$OUT"
cargo build --release -q
run() {
  local name=$1
  shift
  echo "== $name: $*" >&2
  "$@" > "$OUT/$name.md"
}
run map_building bench/compare.sh "$RUNS"
run signatures bench/signatures.sh 5 10
run s3 bench/s3.sh "$OUT/s3"
run authors_setup python3 bench/authors_setup.py --runs "$RUNS"
run authors_transitions python3 bench/authors_setup.py --runs "$RUNS" --transitions
run authors_marching_cubes python3 bench/authors_setup.py --runs "$RUNS" --marching-cubes
run subdivision python3 bench/subdivision.py --runs "$RUNS"
run parallel_ceiling python3 bench/parallel_ceiling.py --runs "$RUNS"
run recombine python3 bench/recombine.py --runs "$RUNS"
python3 -m pip install --quiet gmsh
run recombine_cad python3 bench/recombine_cad.py --runs "$RUNS"
python3 -m pip install --quiet vtk scikit-image
run marching_cubes python3 bench/marching_cubes.py --runs "$RUNS"
run python_overhead python3 bench/python_overhead.py target/release/qmesh "$DATA" 5
echo "tables in $OUT" >&2
