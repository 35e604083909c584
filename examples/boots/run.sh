#!/usr/bin/env bash
# 2025 §8 (Fig. 13b): a query with automorphisms edited the same way on every copy.
# Eight figures in random orientations get a toe cap on each boot, with and without
# the geometric orientation; each result is compared with the figures drawn directly
# with their toe caps, and pictured.
#   examples/boots/run.sh        (uses $QMESH_BIN, default target/release/qmesh)
set -euo pipefail
cd "$(dirname "$0")"
. ../qmesh_bin.sh
mkdir -p out pictures
python3 boots.py out
for rules in boots boots-unoriented; do
    "$Q" modify out/figures.vtk out/$rules.vtk --rules $rules.toml --json --force > out/$rules.json
    python3 ../same_points.py out/$rules.vtk out/figures_expected.vtk --grid 4.5 > out/$rules.check.json || true
    python3 - "$rules" <<'PY'
import json, sys
name = sys.argv[1]
r = json.load(open(f"out/{name}.json"))["rules"][0]
c = json.load(open(f"out/{name}.check.json"))
misplaced = c["extra"] // 4  # a toe cap put on another side moves its 4 new corners
copies = 8 - len(c["extra_by_cell"])
print(f"{name}.toml: {r['matches']} boots ({r['automorphisms']} automorphisms), {r['modified']} toe caps, "
      f"{r['modified'] - misplaced} of them where drawn, {copies} of 8 figures edited as drawn; "
      f"query {r['query_seconds']:.4f} s, "
      f"extend {r['modify_seconds']:.5f} s; valid: {r['valid']}")
if name == "boots" and (c["extra"] or not r["valid"]):
    sys.exit("boots.toml: the geometric orientation should put every toe cap where drawn")
PY
    "$Q" render out/$rules.vtk -o pictures/$rules.png --color-by label --size 1000,700 -q
    # The second figure alone (its cell of the 4.5 grid), seen closer.
    "$Q" render out/$rules.vtk -o pictures/${rules}_second_figure.png --clip "x>2.25" --clip "x<6.75" \
        --clip "y<2.25" --color-by label --size 800,600 -q
done
"$Q" render out/figures.vtk -o pictures/figures.png --color-by label --size 1000,700 -q
