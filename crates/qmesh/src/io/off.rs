//! OFF surfaces (Geomview): `OFF` header (also COFF/NOFF…), counts, vertices, faces.

use std::io::Write;
use std::path::Path;

use super::error::{IoError, IoResult};
use super::lexer::{Lexer, clip};
use crate::build::IndexedMesh;

/// Parses an ASCII OFF file (per-face colours after the indices are ignored).
pub fn read(path: &Path, data: &[u8]) -> IoResult<IndexedMesh> {
    let mut lx = Lexer::new(path, data, Some(b'#'));
    let head = lx.expect("the 'OFF' header")?;
    if !head.ends_with("OFF") || head.len() > 6 {
        return Err(lx.err(format!("expected the 'OFF' header, found '{}'", clip(head))));
    }
    if head.starts_with("ST") || head.starts_with('4') || head.starts_with('n') {
        return Err(IoError::unsupported(path, format!("OFF variant '{head}' is not supported")));
    }
    let nv = lx.count("vertices", 6)?;
    let nf = lx.count("faces", 2)?;
    let _ne: i64 = lx.parse("the number of edges")?;
    let mut mesh = IndexedMesh::new();
    mesh.points.reserve(nv);
    for _ in 0..nv {
        mesh.points.push(lx.point()?);
        // Skip per-vertex extras (normals, colours) up to the end of the line.
        lx.rest_of_line();
    }
    let mut poly = Vec::new();
    for f in 0..nf {
        let k = lx.count("face vertices", 2)?;
        if k < 3 {
            return Err(lx.err(format!("face {f}: expected at least 3 vertices, found {k}")));
        }
        poly.clear();
        for _ in 0..k {
            poly.push(lx.index(0, nv, "vertex index")?);
        }
        mesh.push_polygon(&poly);
        mesh.poly_lines.push(lx.line());
        lx.rest_of_line();
    }
    Ok(mesh)
}

/// Writes an ASCII OFF file of polygons.
pub fn write(path: &Path, mesh: &IndexedMesh, w: &mut dyn Write) -> IoResult<()> {
    let io = |e| IoError::io(path, e);
    writeln!(w, "OFF\n{} {} 0", mesh.points.len(), mesh.nb_polygons()).map_err(io)?;
    for p in &mesh.points {
        writeln!(w, "{} {} {}", p[0], p[1], p[2]).map_err(io)?;
    }
    for i in 0..mesh.nb_polygons() {
        let p = mesh.polygon(i);
        write!(w, "{}", p.len()).map_err(io)?;
        for v in p {
            write!(w, " {v}").map_err(io)?;
        }
        writeln!(w).map_err(io)?;
    }
    Ok(())
}
