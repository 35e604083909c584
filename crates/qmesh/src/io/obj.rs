//! Wavefront OBJ surfaces: `v` and `f` records (with `v/vt/vn` and negative indices).

use std::io::Write;
use std::path::Path;

use super::error::{IoError, IoResult};
use super::lexer::{Lexer, clip};
use crate::build::IndexedMesh;

/// Parses an OBJ file; records other than `v` and `f` are ignored.
pub fn read(path: &Path, data: &[u8]) -> IoResult<IndexedMesh> {
    let mut lx = Lexer::new(path, data, Some(b'#'));
    let mut mesh = IndexedMesh::new();
    let mut poly = Vec::new();
    while let Some(rec) = lx.token() {
        match rec {
            "v" => {
                mesh.points.push(lx.point()?);
                lx.rest_of_line();
            }
            "f" | "fo" => {
                poly.clear();
                let line = lx.rest_of_line();
                for tok in line.split_whitespace() {
                    let first = tok.split('/').next().unwrap_or("");
                    let i: i64 = first
                        .parse()
                        .map_err(|_| lx.err(format!("expected a vertex index in face, found '{}'", clip(tok))))?;
                    let n = mesh.points.len() as i64;
                    let idx = if i < 0 { n + i } else { i - 1 };
                    if i == 0 || idx < 0 || idx >= n {
                        return Err(lx.err(format!("face vertex index {i} is out of range (1..={n} or -{n}..=-1)")));
                    }
                    poly.push(idx as u32);
                }
                if poly.len() < 3 {
                    return Err(lx.err(format!("expected at least 3 vertices in a face, found {}", poly.len())));
                }
                mesh.push_polygon(&poly);
                mesh.poly_lines.push(lx.line());
            }
            _ => {
                lx.rest_of_line();
            }
        }
    }
    if mesh.nb_polygons() == 0 {
        return Err(lx.err("expected at least one 'f' record (no faces in the file)"));
    }
    Ok(mesh)
}

/// Writes an OBJ file of polygons.
pub fn write(path: &Path, mesh: &IndexedMesh, w: &mut dyn Write) -> IoResult<()> {
    let io = |e| IoError::io(path, e);
    writeln!(w, "# written by qmesh").map_err(io)?;
    for p in &mesh.points {
        writeln!(w, "v {} {} {}", p[0], p[1], p[2]).map_err(io)?;
    }
    for i in 0..mesh.nb_polygons() {
        write!(w, "f").map_err(io)?;
        for v in mesh.polygon(i) {
            write!(w, " {}", v + 1).map_err(io)?;
        }
        writeln!(w).map_err(io)?;
    }
    Ok(())
}
