#!/usr/bin/env bash
# Mutation testing of the map's core and of the query-modify engine (cargo-mutants).
#
#   scripts/mutants.sh core      # cmap/sew.rs, cmap/validity.rs, signature/{face,volume}.rs, replace/face.rs
#   scripts/mutants.sh engine    # query/ and modify/
#   scripts/mutants.sh core -F sew1   # extra arguments go to cargo-mutants
#
# Each mutant is built with the `mutants` profile (the test profile, incremental) and
# tested by the qmesh crate's fast tests (for the core set: the unit tests and every
# integration test but the slow whole-mesh ones; for the engine set: the unit tests and
# the query-modify suite), so a mutant caught here is caught by a subset of `cargo test`.
# Results: target/mutants-<set>/mutants.out/{caught,missed,timeout,unviable}.txt
set -euo pipefail
cd "$(dirname "$0")/.."
set_name="${1:-core}"
shift || true
case "$set_name" in
core) files=(cmap/sew.rs cmap/validity.rs signature/face.rs signature/volume.rs replace/face.rs) ;;
engine) files=('query/*.rs' 'modify/*.rs') ;;
*) echo "mutants.sh: unknown set '$set_name' (expected core or engine)" >&2; exit 2 ;;
esac
if ! command -v cargo-mutants >/dev/null; then
    cargo install cargo-mutants --locked --version 27.1.0
fi
data="${QMESH_DATA:-../shared/data}"
[ -d "$data" ] && export QMESH_DATA="$(cd "$data" && pwd)"
args=()
for f in "${files[@]}"; do args+=(-f "crates/qmesh/src/$f"); done
case "$set_name" in
core) fast_tests=(--lib --test cmap_examples --test signatures --test query_modify --test proptest_ops
    --test proptest_replace --test malformed --test build_extract --test generated_patterns
    --test apps_subdivide --test apps_tet2hex) ;;
# The engine's own tests: its unit tests and the query-modify suite (matching,
# modifying, recombination, terrain, properties).
engine) fast_tests=(--lib --test query_modify) ;;
esac
# Given to the build too, so that each mutant links only the test programs it runs.
for t in "${fast_tests[@]}"; do args+=(--cargo-arg="$t"); done
# Linking a dozen test programs is most of a mutant's build: mold (Debian package
# `mold`) does it several times faster than the default linker.
if command -v mold >/dev/null; then
    export RUSTFLAGS="${RUSTFLAGS:-} -C link-arg=-fuse-ld=mold"
fi
out="target/mutants-$set_name"
mkdir -p "$out"
exec cargo mutants --profile mutants --test-package qmesh --timeout 60 --build-timeout 600 \
    -o "$out" "${args[@]}" "$@"
