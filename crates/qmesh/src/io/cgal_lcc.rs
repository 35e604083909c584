//! CGAL's own polyhedral text format, which the authors' marching-cubes patterns use
//! under the `.mesh` extension (`patterns/cgal/FORMAT.md`; not Medit): `POINTS VOLUMES
//! 3`, the points, then each volume as `k v₀ … v_{k−1}` for a tetrahedron (k = 4) or a
//! prism (k = 6: triangles v₀v₁v₂ and v₃v₄v₅, edges vᵢvᵢ₊₃, as VTK wedges), or as
//! `−n f` and f faces `m w₀ … w_{m−1}` for a polyhedron of n vertices. Indices are
//! 0-based. Orientation is not fixed by the format: cells are oriented by their signed
//! volume when the map is built (`fix_orientation`).

use std::path::Path;

use super::error::IoResult;
use super::lexer::Lexer;
use crate::build::{CellKind, IndexedMesh};

/// Whether `data` looks like this format rather than Medit: it starts with a number.
pub fn looks_like(data: &[u8]) -> bool {
    let start = data.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(data.len());
    data.get(start).is_some_and(|b| b.is_ascii_digit())
}

/// Parses the format.
///
/// # Errors
/// A malformed header, count, index or cell, with the line.
pub fn read(path: &Path, data: &[u8]) -> IoResult<IndexedMesh> {
    let mut lx = Lexer::new(path, data, Some(b'#'));
    let np = lx.count("points", 6)?;
    let nv = lx.count("volumes", 4)?;
    let dim: i64 = lx.parse("the dimension (3)")?;
    if dim != 3 {
        return Err(lx.err(format!("expected dimension 3, found {dim}")));
    }
    let mut mesh = IndexedMesh::new();
    mesh.points.reserve(np);
    for _ in 0..np {
        mesh.points.push(lx.point()?);
    }
    for _ in 0..nv {
        let k: i64 = lx.parse("a volume's vertex count (4, 6, or −n for a polyhedron)")?;
        let line = lx.line();
        match k {
            4 | 6 => {
                let nodes: Vec<u32> = (0..k).map(|_| lx.index(0, np, "a vertex index")).collect::<Result<_, _>>()?;
                mesh.push_cell(if k == 4 { CellKind::Tet } else { CellKind::Prism }, &nodes, None);
            }
            k if k < 0 => {
                let nf = lx.count("faces", 4)?;
                let mut stream = vec![nf as u32];
                for _ in 0..nf {
                    let m = lx.count("face vertices", 2)?;
                    if m < 3 {
                        return Err(lx.err(format!("a face needs at least 3 vertices, found {m}")));
                    }
                    stream.push(m as u32);
                    for _ in 0..m {
                        stream.push(lx.index(0, np, "a vertex index")?);
                    }
                }
                mesh.push_cell(CellKind::Polyhedron, &stream, None);
            }
            _ => return Err(lx.err(format!("expected a volume of 4 or 6 vertices or a polyhedron (−n), found {k}"))),
        }
        mesh.cell_lines.push(line);
    }
    if let Some(extra) = lx.token() {
        return Err(lx.err(format!("expected the end of the file after {nv} volumes, found '{extra}'")));
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tetrahedron_and_a_polyhedron_read_and_bad_counts_are_refused() {
        let text =
            "5 2 3\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n4 0 1 2 3\n-4 4\n 3 1 2 4\n 3 1 3 2\n 3 2 3 4\n 3 1 4 3\n";
        let m = read(Path::new("t.mesh"), text.as_bytes()).unwrap();
        assert_eq!(m.kinds, vec![CellKind::Tet, CellKind::Polyhedron]);
        assert!(looks_like(text.as_bytes()) && !looks_like(b"MeshVersionFormatted 2"));
        let e = read(Path::new("t.mesh"), b"5 2 3\n0 0 0\n").unwrap_err().to_string();
        assert!(e.contains("t.mesh") && e.contains("line"), "{e}");
        let e = read(Path::new("t.mesh"), b"1 1 3\n0 0 0\n5 0 0 0 0 0\n").unwrap_err().to_string();
        assert!(e.contains("found 5"), "{e}");
    }
}
