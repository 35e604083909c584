# Sourced by the example scripts (after `cd` into their folder): `root` is the
# repository, `Q` the qmesh binary ($QMESH_BIN, default target/release/qmesh, built
# when missing).
root=$(cd ../.. && pwd)
Q="${QMESH_BIN:-$root/target/release/qmesh}"
[ -x "$Q" ] || (cd "$root" && cargo build --release --quiet)
