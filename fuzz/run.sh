#!/usr/bin/env bash
# Fuzz every reader with cargo-fuzz (libFuzzer), seeded from ../shared/data.
# usage: fuzz/run.sh SECONDS_PER_TARGET [TARGET...]
# cargo-fuzz needs unstable rustc flags: this script sets RUSTC_BOOTSTRAP=1 for the fuzz
# build only (the project itself builds on stable). Corpora and crash artifacts stay in
# fuzz/corpus and fuzz/artifacts (not committed); crashes found become regression tests.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET=${1:-60}
shift || true
DATA=${QMESH_DATA:-$(cd .. && pwd)/shared/data}
command -v cargo-fuzz >/dev/null || cargo install cargo-fuzz --locked
declare -A EXT=([read_vtk]=vtk [read_vtu]=vtu [read_medit]=mesh [read_msh]=msh [read_off]=off [read_obj]=obj [read_stl]=stl [read_ply]=ply [read_moka]=moka [read_pattern]=pattern)
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=("${!EXT[@]}")
for t in "${TARGETS[@]}"; do
  mkdir -p "fuzz/corpus/$t"
  # Seeds: the shared files of this format under 300 KB (copies stay outside git); the
  # pattern target takes the papers' pattern files.
  if [ "$t" = read_pattern ]; then
    find "$DATA/patterns" -type f \( -name "*.moka" -o -name "*.vtk" -o -name "*.off" \) -size -300k -exec cp -n {} "fuzz/corpus/$t/" \; 2>/dev/null || true
  else
    find "$DATA" -name "*.${EXT[$t]}" -size -300k -exec cp -n {} "fuzz/corpus/$t/" \; 2>/dev/null || true
  fi
  echo "== $t: ${SECONDS_PER_TARGET}s"
  log="fuzz/artifacts/$t.log"
  mkdir -p fuzz/artifacts
  status=0
  RUSTC_BOOTSTRAP=1 cargo fuzz run "$t" "fuzz/corpus/$t" -- -max_total_time="$SECONDS_PER_TARGET" -rss_limit_mb=2048 -max_len=1048576 >"$log" 2>&1 || status=$?
  grep -E "^#[0-9]+ +DONE|Done [0-9]+ runs|ERROR|panicked|SUMMARY|Test unit written" "$log" || true
  if [ "$status" -ne 0 ]; then
    echo "fuzz target $t failed (exit $status); see $log"
    failed=1
  fi
done
exit "${failed:-0}"
