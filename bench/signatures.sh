#!/usr/bin/env bash
# Signatures vs the direct isomorphism test (2022 §2.3) when every one of the 325
# Jaillet-Lobos patterns is a candidate: the input is the boundary of each pattern as
# one cell (COPIES times), flagged by the same geometric corner rule as the patterns.
# usage: bench/signatures.sh [RUNS] [COPIES]   (prints a Markdown table)
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${1:-5}
COPIES=${2:-10}
DATA=${QMESH_DATA:-$(cd .. && pwd)/shared/data}
P="$DATA/patterns/cgal/hexa-325-patterns"
WORK=${TMPDIR:-/tmp}/qmesh-bench
mkdir -p "$WORK"
cargo build --release -q
Q=target/release/qmesh
$Q patterns boundaries "$P" -o "$WORK/b325.vtk" --copies "$COPIES" >&2
python3 bench/measure.py "$RUNS" signatures -- "$Q" replace "$WORK/b325.vtk" "$WORK/r_sig.vtk" --flags geometric --patterns "$P" --json \
  --- direct -- "$Q" replace "$WORK/b325.vtk" "$WORK/r_dir.vtk" --flags geometric --no-signatures --patterns "$P" --json \
  > "$WORK/sig.jsonl"
python3 - "$WORK/sig.jsonl" <<'PY'
import json, sys
s, d = [json.loads(l) for l in open(sys.argv[1])]
print("| mode | cells | matched | query (s) | whole process (s) |")
print("|---|---|---|---|---|")
for r in (s, d):
    o = r["output"]
    print(f"| {r['label']} | {o['volumes_before']} | {o['volumes_before'] - o['unmatched_volumes']} | {o['query_seconds']:.3f} | {r['seconds']:.3f} |")
same = s["output"]["volumes"] == d["output"]["volumes"] and s["output"]["cell_types"] == d["output"]["cell_types"]
print(f"\nratio direct/signatures: query {d['output']['query_seconds'] / s['output']['query_seconds']:.1f}x, "
      f"whole process {d['seconds'] / s['seconds']:.1f}x; identical output: {same}")
PY
