//! VTK XML unstructured grids (`.vtu`) through the `vtkio` crate; the cell layout is
//! then interpreted exactly as for legacy files.

use std::io::Write;
use std::path::Path;

use vtkio::model::{
    Attribute, Attributes, ByteOrder, CellType, Cells, DataArray, DataSet, IOBuffer, Piece, UnstructuredGridPiece,
    Version, VertexNumbers, Vtk,
};

use super::error::{IoError, IoResult, Location};
use super::vtk_legacy::{CellList, INT_ARRAYS, LABEL_ARRAYS, assemble};
use crate::build::{CellKind, CellValues, IndexedMesh};

fn flat_to_offsets(num_cells: u32, flat: &[u32]) -> Option<CellList> {
    let mut offs = vec![0usize];
    let mut conn = Vec::with_capacity(flat.len());
    let mut k = 0usize;
    for _ in 0..num_cells {
        let m = *flat.get(k)? as usize;
        conn.extend(flat.get(k + 1..k + 1 + m)?.iter().map(|&v| v as i64));
        offs.push(conn.len());
        k += 1 + m;
    }
    Some(CellList { offsets: offs, conn, lines: Vec::new() })
}

/// The line where `needle` first occurs.
fn find_line(data: &[u8], needle: &[u8]) -> Option<usize> {
    let at = data.windows(needle.len()).position(|w| w == needle)?;
    Some(1 + data[..at].iter().filter(|&&b| b == b'\n').count())
}

/// The line of the first XML syntax error (or of an element never closed), or, for a
/// well-formed file that is not a VTK UnstructuredGrid, of its root element (vtkio's
/// errors carry no position).
fn xml_error_line(data: &[u8]) -> usize {
    use quick_xml::events::Event;
    let mut reader = quick_xml::Reader::from_reader(data);
    let mut buf = Vec::new();
    let (mut root, mut open) = (None, Vec::new());
    let at = loop {
        let before = reader.buffer_position() as usize;
        match reader.read_event_into(&mut buf) {
            Err(_) => break reader.error_position() as usize,
            // An element left open at the end: point at its start tag.
            Ok(Event::Eof) => break open.last().copied().or(root).unwrap_or(0),
            Ok(Event::Start(_)) => {
                root.get_or_insert(before);
                open.push(before);
            }
            Ok(Event::Empty(_)) => {
                root.get_or_insert(before);
            }
            Ok(Event::End(_)) => {
                open.pop();
            }
            Ok(_) => {}
        }
        buf.clear();
    };
    1 + data[..at.min(data.len())].iter().filter(|&&b| b == b'\n').count()
}

/// A person's reading of a vtkio error (its `Display` shows Rust debug text for the
/// nested errors) and the line it is about.
fn describe(e: &vtkio::Error, data: &[u8]) -> (String, usize) {
    use vtkio::xml::{Error as XmlError, ValidationError as V};
    let at_syntax = xml_error_line(data);
    match e {
        vtkio::Error::XML(XmlError::Validation(V::DataArraySizeMismatch { name, expected, actual })) => {
            // vtkio names the point coordinates "".
            let (what, line) = if name.is_empty() {
                ("the point coordinates".to_string(), find_line(data, b"<Points"))
            } else {
                (format!("DataArray '{name}'"), find_line(data, format!("Name=\"{name}\"").as_bytes()))
            };
            (format!("{what} hold {actual} values, {expected} expected"), line.unwrap_or(at_syntax))
        }
        vtkio::Error::XML(XmlError::Validation(v)) => (format!("invalid VTK XML content: {v}"), at_syntax),
        vtkio::Error::XML(XmlError::XML(x)) => (format!("malformed XML: {x}"), at_syntax),
        vtkio::Error::XML(XmlError::Base64Decode(_)) => ("binary data that is not valid base64".into(), at_syntax),
        vtkio::Error::XML(XmlError::Deserialization(d)) => {
            (format!("expected a VTK XML UnstructuredGrid file: {d}"), at_syntax)
        }
        other => (format!("expected a VTK XML UnstructuredGrid file: {other}"), at_syntax),
    }
}

/// Parses a `.vtu` file (inline or appended data, ASCII, base64 or raw, compressed or not).
pub fn read(path: &Path, data: &[u8]) -> IoResult<IndexedMesh> {
    super::vtu_headers::check(path, data)?;
    let vtk = Vtk::parse_xml(std::io::BufReader::new(data)).map_err(|e| {
        let (msg, line) = describe(&e, data);
        IoError::Parse { path: path.into(), at: Location::Line(line), msg }
    })?;
    // vtkio keeps no positions: point content errors at the <Cells> element (what
    // they are about), or the file's first line.
    let cells_line = find_line(data, b"<Cells").unwrap_or(1);
    let err = |m: String| IoError::Parse { path: path.into(), at: Location::Line(cells_line), msg: m };
    let file_pieces = match vtk.data {
        DataSet::UnstructuredGrid { pieces, .. } => pieces,
        _ => return Err(err("only UnstructuredGrid .vtu files are supported".into())),
    };
    let mut all = IndexedMesh::new();
    let mut pieces: Vec<IndexedMesh> = Vec::new();
    for piece in file_pieces {
        let p: UnstructuredGridPiece = match piece {
            Piece::Inline(p) => *p,
            _ => return Err(err("pieces stored in other files are not supported".into())),
        };
        let points: Vec<f64> = p.points.cast_into().ok_or_else(|| err("points are not numbers".into()))?;
        if points.iter().any(|x| !x.is_finite()) {
            return Err(err("expected finite point coordinates".into()));
        }
        let types: Vec<i64> = p.cells.types.iter().map(|&t| t as u8 as i64).collect();
        let (n, flat) = p.cells.cell_verts.into_legacy();
        let cells =
            flat_to_offsets(n, &flat).ok_or_else(|| err("cell connectivity is shorter than its offsets".into()))?;
        let labels = p.data.cell.iter().find_map(|a| match a {
            Attribute::DataArray(DataArray { name, data, .. }) if LABEL_ARRAYS.contains(&name.as_str()) => {
                data.cast_into::<i64>()
            }
            _ => None,
        });
        let mut mesh = assemble(
            &err,
            points.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
            Some(cells),
            Some(types),
            Vec::new(),
            labels,
        )?;
        // Arrays qmesh wrote (one value per cell, no cell skipped) come back as they were.
        for a in &p.data.cell {
            if let Attribute::DataArray(DataArray { name, data, .. }) = a
                && INT_ARRAYS.contains(&name.as_str())
                && let Some(v) = data.clone().cast_into::<i64>()
                && v.len() == mesh.nb_cells()
                && mesh.is_volume()
            {
                mesh.set_cell_array(name, CellValues::Int(v.iter().map(|&x| x as i32).collect()));
            }
        }
        pieces.push(mesh);
    }
    if pieces.len() == 1 {
        return Ok(pieces.pop().unwrap_or_default());
    }
    pieces.into_iter().for_each(|m| merge(&mut all, m));
    Ok(all)
}

fn merge(all: &mut IndexedMesh, m: IndexedMesh) {
    let base = all.points.len() as u32;
    all.points.extend_from_slice(&m.points);
    for i in 0..m.nb_cells() {
        let (k, nodes) = m.cell(i);
        let shifted: Vec<u32> = if k == CellKind::Polyhedron {
            let mut out = vec![nodes[0]];
            let mut j = 1;
            while j < nodes.len() {
                let c = nodes[j] as usize;
                out.push(nodes[j]);
                out.extend(nodes[j + 1..j + 1 + c].iter().map(|v| v + base));
                j += 1 + c;
            }
            out
        } else {
            nodes.iter().map(|v| v + base).collect()
        };
        all.push_cell(k, &shifted, m.label(i));
    }
    for i in 0..m.nb_polygons() {
        all.push_polygon(&m.polygon(i).iter().map(|v| v + base).collect::<Vec<_>>());
    }
    all.warnings.extend(m.warnings);
}

/// Writes a `.vtu` file (binary base64 inline data) with a `label` cell array when
/// the mesh has labels.
///
/// # Errors
/// Polyhedra are not supported by the XML writer we use; write legacy `.vtk` instead.
pub fn write(path: &Path, mesh: &IndexedMesh, w: &mut dyn Write) -> IoResult<()> {
    let mut types = Vec::new();
    let mut conn: Vec<u64> = Vec::new();
    let mut offsets: Vec<u64> = Vec::new();
    if mesh.is_volume() {
        for i in 0..mesh.nb_cells() {
            let (k, nodes) = mesh.cell(i);
            types.push(match k {
                CellKind::Tet => CellType::Tetra,
                CellKind::Pyramid => CellType::Pyramid,
                CellKind::Prism => CellType::Wedge,
                CellKind::Hex => CellType::Hexahedron,
                CellKind::Polyhedron => {
                    return Err(IoError::unsupported(path, "polyhedra cannot be written to .vtu yet; use .vtk"));
                }
            });
            conn.extend(nodes.iter().map(|&v| v as u64));
            offsets.push(conn.len() as u64);
        }
    } else {
        for i in 0..mesh.nb_polygons() {
            let p = mesh.polygon(i);
            types.push(match p.len() {
                3 => CellType::Triangle,
                4 => CellType::Quad,
                _ => CellType::Polygon,
            });
            conn.extend(p.iter().map(|&v| v as u64));
            offsets.push(conn.len() as u64);
        }
    }
    let mut data = Attributes::new();
    let cell_type: Vec<i32> = types.iter().map(|&t| t as i32).collect();
    data.cell.push(Attribute::scalars("cell_type", 1).with_data(IOBuffer::I32(cell_type)));
    if mesh.is_volume() && mesh.cell_array("scaled_jacobian").is_none() {
        let q = crate::build::scaled_jacobians(mesh);
        data.cell.push(Attribute::scalars("scaled_jacobian", 1).with_data(IOBuffer::F64(q)));
    }
    if mesh.is_volume() && !mesh.labels.is_empty() {
        data.cell.push(Attribute::scalars("label", 1).with_data(IOBuffer::I32(mesh.labels.clone())));
    }
    for a in &mesh.cell_arrays {
        let buf = match &a.values {
            CellValues::Int(v) => IOBuffer::I32(v.clone()),
            CellValues::Float(v) => IOBuffer::F64(v.clone()),
        };
        data.cell.push(Attribute::scalars(a.name.as_str(), 1).with_data(buf));
    }
    let piece = UnstructuredGridPiece {
        points: IOBuffer::F64(mesh.points.iter().flatten().copied().collect()),
        cells: Cells { cell_verts: VertexNumbers::XML { connectivity: conn, offsets }, types },
        data,
    };
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        data: DataSet::inline(piece),
        file_path: None,
    };
    vtk.write_xml(w).map_err(|e| IoError::unsupported(path, format!("VTU writer: {e}")))
}
