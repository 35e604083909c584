#!/usr/bin/env bash
# 2025 §7.4, Table 2: a 128×128 voxel terrain (step 1), 50 flat spots by query-apply
# (step 2), a house on each by query-extend (step 3); counts and times of each step,
# and pictures of the result.
#   examples/terrain/run.sh [SIZE]     (uses $QMESH_BIN, default target/release/qmesh)
set -euo pipefail
cd "$(dirname "$0")"
. ../qmesh_bin.sh
size="${1:-128}"
mkdir -p out pictures
"$Q" generate terrain --size "$size" --base 12 --seed 1 -o out/terrain.vtk --json > out/step1.json
"$Q" modify out/terrain.vtk out/spots.vtk --rules flatten.toml --json --force > out/step2.json
"$Q" modify out/spots.vtk out/houses.vtk --rules houses.toml --json --force > out/step3.json
python3 - <<'PY'
import json
s1, s2, s3 = (json.load(open(f"out/step{i}.json")) for i in (1, 2, 3))
r2, r3 = s2["rules"][0], s3["rules"][0]
print("| Step | Volumes | Darts | Time (s) | paper: volumes, darts, time (s) |")
print("|---|---|---|---|---|")
t1 = s1["generate_seconds"]  # height map + the 3-map of the voxels
print(f"| (1) grid | {s1['volumes']:,} | {s1['darts']:,} | {t1:.3f} | 16,384, 425,984, 0.028 |")
for step, r, paper in (("(2) spots", r2, "15,984, 419,984, 0.012 (0.008 query, 0.004 apply)"),
                       ("(3) houses", r3, "16,134, 431,684, 0.68 (0.62 query, 0.06 extend)")):
    q, m = r["query_seconds"], r["modify_seconds"]
    print(f"| {step} | {r['volumes_after']:,} | {r['darts_after']:,} | {q + m:.3f} ({q:.3f} query, {m:.4f} {r['op']}) | {paper} |")
print(f"matches: spots {r2['matches']} ({r2['selected']} selected), houses {r3['matches']} ({r3['selected']} selected); valid: {r2['valid'] and r3['valid']}")
PY
"$Q" render out/terrain.vtk -o pictures/terrain.png --no-edges --shrink 1 -q
"$Q" render out/houses.vtk -o pictures/houses.png --no-edges --shrink 1 -q
"$Q" render out/houses.vtk -o pictures/houses_detail.png --clip "x<20%" -q
