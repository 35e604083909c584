#!/usr/bin/env bash
# 2025 §7.3 and §8 (Figs. 9, 10, 13a): surface models made of closed parts, each part one
# volume of the 3-map. A flange on every nut: an extend glues it on as a second part (a
# non-manifold intermediate), a replace with `eps` boundary merges the pair again.
#  1. nuts.toml on a synthetic model (nuts.py): six nuts and two look-alike spacers in
#     random poses; the spacers must stay as they are.
#  2. the AS1 assembly (STEP in the shared data) surface-meshed with gmsh (PyPI): the
#     instances whose meshes came out with the same topology, then all nuts at once.
#   examples/parts/run.sh     (uses $QMESH_BIN; AS1 needs gmsh and $QMESH_DATA)
set -euo pipefail
cd "$(dirname "$0")"
. ../qmesh_bin.sh
mkdir -p out/as1 pictures
report() {  # per-rule counts of a `qmesh modify --json` file
    python3 - "$1" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
for r in j["rules"]:
    print(f"  {r['rule']} ({r['op']}): {r['matches']} matches, {r['modified']} modified, volumes "
          f"{r['volumes_before']} → {r['volumes_after']}, darts {r['darts_before']:,} → {r['darts_after']:,}, "
          f"query {r['query_seconds']:.4f} s, {r['op']} {r['modify_seconds']:.5f} s, valid {r['valid']}")
PY
}

# 1. The synthetic model; with max_residual the result is the model drawn with flanged
#    nuts, point for point (the command fails otherwise); without, the spacers change.
python3 nuts.py out
for rules in nuts nuts-topology-only; do
    echo "$rules.toml:"
    "$Q" modify out/nuts.vtk out/${rules}_result.vtk --rules $rules.toml --json --force > out/$rules.json
    report out/$rules.json
    same=0
    python3 ../same_points.py out/${rules}_result.vtk out/nuts_expected.vtk --grid 4 > out/$rules.check.json || same=$?
    echo "  against the model drawn with flanged nuts: $(cat out/$rules.check.json)"
    [ "$rules" = nuts ] && [ "$same" != 0 ] && { echo "nuts.toml: the spacers or a nut came out wrong" >&2; exit 1; }
    "$Q" render out/${rules}_result.vtk -o pictures/$rules.png --color-by label --size 1000,600 -q
done
"$Q" render out/nuts.vtk -o pictures/nuts_before.png --color-by label --size 1000,600 -q

# 2. AS1.
step="${QMESH_DATA:-$root/../shared/data}/cad/as1-tu-203.stp"
why=""
[ -f "$step" ] || why="$step not found (set QMESH_DATA)"
python3 -c "import gmsh" 2>/dev/null || why="gmsh is not installed (python3 -m pip install gmsh)"
if [ -n "$why" ]; then
    [ "${QMESH_REQUIRE_DATA:-0}" = 1 ] && { echo "examples/parts: $why" >&2; exit 1; }
    echo "skipping AS1: $why"
    exit 0
fi
echo "AS1 (gmsh surface meshes; classes = instances whose meshes have the same topology):"
python3 as1.py "$step" out/as1 "$Q" | sed 's/^/  /'
"$Q" modify out/as1/as1.vtk out/as1/as1_flanged.vtk --rules out/as1/flanges.toml --json --force > out/as1/modify.json
report out/as1/modify.json
python3 as1.py --check out/as1 out/as1/as1_flanged.vtk | sed 's/^/  /'
"$Q" render out/as1/as1.vtk -o pictures/as1.png --color-by label --no-edges --shrink 1 -q
# A nut under an L-bracket (the bolt and the bracket clipped away), before and after.
nut=(--clip "x>14" --clip "x<36" --clip "y>66" --clip "y<84" --clip "z>-8" --clip "z<0.5" --view -60,-30 --shrink 1 --size 800,600)
"$Q" render out/as1/as1.vtk -o pictures/as1_nut.png "${nut[@]}" -q
"$Q" render out/as1/as1_flanged.vtk -o pictures/as1_nut_flanged.png "${nut[@]}" -q
