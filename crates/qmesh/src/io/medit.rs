//! Medit `.mesh` (INRIA, ASCII): versions 1 (float) and 2 (double), 1-based indices,
//! each vertex/element line ends with a reference kept as the volume label (GUIDE §3).

use std::io::Write;
use std::path::Path;

use super::error::{IoError, IoResult};
use super::lexer::Lexer;
use crate::build::{CellKind, IndexedMesh};

/// Elements we read: keyword, nodes per element, volume kind (None = surface polygon).
const ELEMENTS: &[(&str, usize, Option<CellKind>)] = &[
    ("Tetrahedra", 4, Some(CellKind::Tet)),
    ("Pyramids", 5, Some(CellKind::Pyramid)),
    ("Prisms", 6, Some(CellKind::Prism)),
    ("Hexahedra", 8, Some(CellKind::Hex)),
    ("Triangles", 3, None),
    ("Quadrilaterals", 4, None),
];

/// Parses a Medit mesh. Volume cells win over surface polygons when both are present
/// (the polygons are then counted as skipped lower-dimensional cells).
pub fn read(path: &Path, data: &[u8]) -> IoResult<IndexedMesh> {
    let mut lx = Lexer::new(path, data, Some(b'#'));
    let mut mesh = IndexedMesh::new();
    let mut dim = 3usize;
    let mut saw_header = false;
    let mut polygons: Vec<(Vec<u32>, u32, i32)> = Vec::new();
    let mut skipped = 0usize;
    while let Some(kw) = lx.token() {
        match kw {
            "MeshVersionFormatted" => {
                let v: i64 = lx.parse("a format version (1 or 2)")?;
                if !(1..=4).contains(&v) {
                    return Err(lx.err(format!("expected format version 1 or 2, found {v}")));
                }
                saw_header = true;
            }
            "Dimension" => {
                dim = lx.parse("the dimension (2 or 3)")?;
                if dim != 2 && dim != 3 {
                    return Err(lx.err(format!("expected dimension 2 or 3, found {dim}")));
                }
            }
            "Vertices" => {
                let n = lx.count("vertices", 2 * (dim + 1))?;
                mesh.points.reserve(n);
                for _ in 0..n {
                    let x = lx.f64("an x coordinate")?;
                    let y = lx.f64("a y coordinate")?;
                    let z = if dim == 3 { lx.f64("a z coordinate")? } else { 0.0 };
                    lx.int("a vertex reference (integer)")?;
                    mesh.points.push([x, y, z]);
                }
            }
            "End" => break,
            _ => {
                if let Some(&(name, k, kind)) = ELEMENTS.iter().find(|e| e.0 == kw) {
                    let n = lx.count(name, 2 * (k + 1))?;
                    let np = mesh.points.len();
                    let mut nodes = vec![0u32; k];
                    for _ in 0..n {
                        for slot in nodes.iter_mut() {
                            *slot = lx.index(1, np, "vertex index")?;
                        }
                        let r = lx.int("an element reference (integer)")?;
                        let r =
                            i32::try_from(r).map_err(|_| lx.err(format!("reference {r} does not fit in 32 bits")))?;
                        match kind {
                            Some(kind) => {
                                mesh.push_cell(kind, &nodes, Some(r));
                                mesh.cell_lines.push(lx.line());
                            }
                            None => polygons.push((nodes.clone(), lx.line(), r)),
                        }
                    }
                } else if kw.starts_with(|c: char| c.is_ascii_alphabetic()) {
                    // Other sections (Edges, Corners, Ridges, Normals…): skip their numbers.
                    skipped_section(&mut lx, &mut skipped);
                } else if !saw_header {
                    return Err(lx.err(format!("expected 'MeshVersionFormatted', found '{}'", super::lexer::clip(kw))));
                } else {
                    return Err(lx.err(format!("expected a keyword, found '{}'", super::lexer::clip(kw))));
                }
            }
        }
    }
    if !saw_header {
        return Err(lx.err("expected 'MeshVersionFormatted' (not a Medit file?)"));
    }
    if mesh.is_volume() {
        if !polygons.is_empty() {
            mesh.warnings.push(format!(
                "skipped {} boundary triangles/quadrilaterals (volume mesh; their references are kept as face labels)",
                polygons.len()
            ));
            mesh.face_labels = polygons.into_iter().map(|(p, _, r)| (p, r)).collect();
        }
    } else {
        for (p, line, _) in &polygons {
            mesh.push_polygon(p);
            mesh.poly_lines.push(*line);
        }
    }
    if skipped > 0 {
        mesh.warnings.push(format!("skipped {skipped} other Medit sections"));
    }
    Ok(mesh)
}

fn skipped_section(lx: &mut Lexer<'_>, skipped: &mut usize) {
    *skipped += 1;
    while let Some(t) = lx.peek() {
        if t.starts_with(|c: char| c.is_ascii_alphabetic()) {
            break;
        }
        lx.token();
    }
}

/// Writes a Medit mesh (version 2, double precision).
///
/// # Errors
/// Polyhedra cannot be stored in Medit files.
pub fn write(path: &Path, mesh: &IndexedMesh, w: &mut dyn Write) -> IoResult<()> {
    let poly = mesh.kinds.iter().filter(|k| **k == CellKind::Polyhedron).count();
    if poly > 0 {
        return Err(IoError::unsupported(
            path,
            format!("Medit has no polyhedron cells ({poly} in the mesh); write VTK instead"),
        ));
    }
    let io = |e| IoError::io(path, e);
    writeln!(w, "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n{}", mesh.points.len()).map_err(io)?;
    for p in &mesh.points {
        writeln!(w, "{} {} {} 0", p[0], p[1], p[2]).map_err(io)?;
    }
    for &(name, _, kind) in ELEMENTS {
        match kind {
            Some(kind) => {
                let ids: Vec<usize> = (0..mesh.nb_cells()).filter(|&i| mesh.kinds[i] == kind).collect();
                if ids.is_empty() {
                    continue;
                }
                writeln!(w, "\n{name}\n{}", ids.len()).map_err(io)?;
                for i in ids {
                    for &v in mesh.cell(i).1 {
                        write!(w, "{} ", v + 1).map_err(io)?;
                    }
                    writeln!(w, "{}", mesh.label(i).unwrap_or(0)).map_err(io)?;
                }
            }
            None => {
                let k = if name == "Triangles" { 3 } else { 4 };
                let polygons = (0..mesh.nb_polygons()).map(|i| (mesh.polygon(i), 0));
                let labelled = mesh.face_labels.iter().map(|(f, r)| (f.as_slice(), *r));
                let faces: Vec<(&[u32], i32)> = polygons.chain(labelled).filter(|(f, _)| f.len() == k).collect();
                if faces.is_empty() {
                    continue;
                }
                writeln!(w, "\n{name}\n{}", faces.len()).map_err(io)?;
                for (f, r) in faces {
                    for &v in f {
                        write!(w, "{} ", v + 1).map_err(io)?;
                    }
                    writeln!(w, "{r}").map_err(io)?;
                }
            }
        }
    }
    let other = (0..mesh.nb_polygons()).filter(|&i| !(3..=4).contains(&mesh.polygon(i).len())).count();
    if other > 0 {
        return Err(IoError::unsupported(
            path,
            format!("Medit stores only triangles and quadrilaterals ({other} other polygons)"),
        ));
    }
    writeln!(w, "\nEnd").map_err(io)
}
