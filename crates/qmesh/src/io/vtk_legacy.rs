//! VTK legacy files (`.vtk`): ASCII and BINARY (big-endian), UNSTRUCTURED_GRID and
//! POLYDATA, cell layouts of versions ≤ 4.2 (`CELLS n size`) and 5.x (OFFSETS /
//! CONNECTIVITY). Lower-dimensional cells next to volume cells are skipped with a
//! count; cells declared type 10 with 8 indices are read as hexahedra (GUIDE §3).

use std::io::Write;
use std::path::Path;

use super::error::{IoError, IoResult, Location};
use super::lexer::{Lexer, clip};
use crate::build::{CellKind, CellValues, IndexedMesh};

/// Integer cell arrays qmesh writes and reads back (octree level, matched pattern).
pub(super) const INT_ARRAYS: &[&str] = &["level", "pattern_id"];

/// Names of cell arrays read as volume labels.
pub const LABEL_ARRAYS: &[&str] =
    &["CellEntityIds", "gmsh:physical", "gmsh:geometrical", "medit:ref", "label", "labels", "MaterialIds"];

/// A cell list as read: offsets into the flat connectivity, and the source line of
/// each cell when known (ASCII legacy layout).
pub(super) struct CellList {
    pub offsets: Vec<usize>,
    pub conn: Vec<i64>,
    pub lines: Vec<u32>,
}

struct Reader<'a> {
    lx: Lexer<'a>,
    binary: bool,
}

fn type_size(t: &str) -> Option<usize> {
    Some(match t {
        "bit" | "unsigned_char" | "char" => 1,
        "unsigned_short" | "short" => 2,
        "unsigned_int" | "int" | "float" | "vtkIdType" => 4,
        "unsigned_long" | "long" | "double" | "vtktypeint64" | "vtktypeuint64" => 8,
        _ => return None,
    })
}

impl<'a> Reader<'a> {
    fn dtype(&mut self) -> IoResult<(&'a str, usize)> {
        let t = self.lx.expect("a data type (float, double, int…)")?;
        let s = type_size(t).ok_or_else(|| self.lx.err(format!("expected a VTK data type, found '{}'", clip(t))))?;
        Ok((t, s))
    }

    /// Reads `n` numbers of VTK type `t` as f64 (ASCII tokens or big-endian binary).
    fn numbers(&mut self, n: usize, t: &str, size: usize, what: &str) -> IoResult<Vec<f64>> {
        let min = if self.binary { size } else { 2 };
        self.lx.check_count(n as i64, what, min)?;
        let mut out = Vec::with_capacity(n);
        if !self.binary {
            for _ in 0..n {
                out.push(self.lx.f64(what)?);
            }
            return Ok(out);
        }
        self.lx.next_line();
        let bytes = self.lx.bytes(n * size, what)?;
        for c in bytes.chunks_exact(size) {
            let v = match (t, size) {
                ("float", 4) => f32::from_be_bytes(c.try_into().unwrap()) as f64,
                ("double", 8) => f64::from_be_bytes(c.try_into().unwrap()),
                ("unsigned_char" | "bit", 1) => c[0] as f64,
                ("char", 1) => c[0] as i8 as f64,
                ("short", 2) => i16::from_be_bytes(c.try_into().unwrap()) as f64,
                ("unsigned_short", 2) => u16::from_be_bytes(c.try_into().unwrap()) as f64,
                ("unsigned_int", 4) => u32::from_be_bytes(c.try_into().unwrap()) as f64,
                (_, 4) => i32::from_be_bytes(c.try_into().unwrap()) as f64,
                ("unsigned_long" | "vtktypeuint64", 8) => u64::from_be_bytes(c.try_into().unwrap()) as f64,
                (_, 8) => i64::from_be_bytes(c.try_into().unwrap()) as f64,
                _ => unreachable!("type_size covers every type"),
            };
            if !v.is_finite() {
                return Err(self.lx.err_at_byte(format!("expected finite {what}, found {v}")));
            }
            out.push(v);
        }
        Ok(out)
    }

    /// Reads `n` integers (cell connectivity) of type `t`.
    fn integers(&mut self, n: usize, t: &str, size: usize, what: &str) -> IoResult<Vec<i64>> {
        if !self.binary {
            self.lx.check_count(n as i64, what, 2)?;
            let mut out = Vec::with_capacity(n);
            for _ in 0..n {
                out.push(self.lx.int(what)?);
            }
            return Ok(out);
        }
        let v = self.numbers(n, t, size, what)?;
        Ok(v.into_iter().map(|x| x as i64).collect())
    }

    /// Skips one attribute block of CELL_DATA/POINT_DATA with `n` tuples; returns a
    /// label array when the block is one, and sets `named` to a one-component SCALARS
    /// array's name and values (for the integer arrays qmesh writes).
    fn attribute(&mut self, kw: &str, n: usize, named: &mut Option<(String, Vec<i64>)>) -> IoResult<Option<Vec<i64>>> {
        match kw {
            "SCALARS" => {
                let name = self.lx.expect("an array name")?;
                let (t, s) = self.dtype()?;
                let mut ncomp = 1;
                if let Some(tok) = self.lx.peek()
                    && tok != "LOOKUP_TABLE"
                    && let Ok(k) = tok.parse::<usize>()
                {
                    self.lx.token();
                    ncomp = k.clamp(1, 4);
                }
                if self.lx.peek() == Some("LOOKUP_TABLE") {
                    self.lx.token();
                    self.lx.expect("a lookup table name")?;
                }
                let v = self.integers_or_floats(n * ncomp, t, s, name)?;
                if LABEL_ARRAYS.contains(&name) {
                    return Ok(Some(v));
                }
                if ncomp == 1 && INT_ARRAYS.contains(&name) {
                    *named = Some((name.to_string(), v));
                }
                Ok(None)
            }
            "VECTORS" | "NORMALS" | "TENSORS" => {
                self.lx.expect("an array name")?;
                let (t, s) = self.dtype()?;
                let k = if kw == "TENSORS" { 9 } else { 3 };
                self.numbers(n * k, t, s, kw)?;
                Ok(None)
            }
            "TEXTURE_COORDINATES" => {
                self.lx.expect("an array name")?;
                let k: usize = self.lx.parse("the number of texture components")?;
                let (t, s) = self.dtype()?;
                self.numbers(n * k.min(3), t, s, kw)?;
                Ok(None)
            }
            "COLOR_SCALARS" => {
                self.lx.expect("an array name")?;
                let k: usize = self.lx.parse("the number of colour components")?;
                let (t, s) = if self.binary { ("unsigned_char", 1) } else { ("float", 4) };
                self.numbers(n * k.min(4), t, s, kw)?;
                Ok(None)
            }
            "LOOKUP_TABLE" => {
                self.lx.expect("a lookup table name")?;
                let k = self.lx.count("lookup table entries", 4)?;
                let (t, s) = if self.binary { ("unsigned_char", 1) } else { ("float", 4) };
                self.numbers(k * 4, t, s, kw)?;
                Ok(None)
            }
            "FIELD" => {
                self.lx.expect("a field name")?;
                let arrays = self.lx.count("field arrays", 8)?;
                let mut labels = None;
                for _ in 0..arrays {
                    let name = self.lx.expect("an array name")?;
                    let k: usize = self.lx.parse("the number of components")?;
                    let tuples: usize = self.lx.parse("the number of tuples")?;
                    let (t, s) = self.dtype()?;
                    let total = k.checked_mul(tuples).ok_or_else(|| self.lx.err("array size overflows"))?;
                    let v = self.integers_or_floats(total, t, s, name)?;
                    if LABEL_ARRAYS.contains(&name) && k == 1 {
                        labels = Some(v);
                    }
                }
                Ok(labels)
            }
            "METADATA" => {
                while let Some(l) = (self.lx.remaining() > 0).then(|| self.lx.rest_of_line()) {
                    if l.trim().is_empty() {
                        break;
                    }
                }
                Ok(None)
            }
            other => Err(self.lx.err(format!("expected a data attribute (SCALARS, FIELD…), found '{}'", clip(other)))),
        }
    }

    fn integers_or_floats(&mut self, n: usize, t: &str, s: usize, what: &str) -> IoResult<Vec<i64>> {
        Ok(self.numbers(n, t, s, what)?.into_iter().map(|x| x as i64).collect())
    }

    /// Cell connectivity as (offsets, flat ids), legacy or 5.x layout.
    fn cells(&mut self) -> IoResult<CellList> {
        let n = self.lx.count("cells", 2)?;
        let size: i64 = self.lx.parse("the size of the cell list")?;
        let size = self.lx.check_count(size, "cell list entries", if self.binary { 4 } else { 2 })?;
        if self.lx.peek() == Some("OFFSETS") {
            self.lx.token();
            let (t, s) = self.dtype()?;
            let offsets = self.integers(n, t, s, "cell offsets")?;
            self.lx.expect_word("CONNECTIVITY")?;
            let (t, s) = self.dtype()?;
            let conn = self.integers(size, t, s, "cell connectivity")?;
            let mut offs = Vec::with_capacity(n);
            for (k, &o) in offsets.iter().enumerate() {
                if o < 0 || o as usize > conn.len() || (k > 0 && o < offsets[k - 1]) {
                    return Err(self
                        .lx
                        .err(format!("cell offset {o} is out of order or beyond the connectivity ({})", conn.len())));
                }
                offs.push(o as usize);
            }
            if offs.first().is_some_and(|&o| o != 0) {
                return Err(self.lx.err("the first cell offset must be 0"));
            }
            return Ok(CellList { offsets: offs, conn, lines: Vec::new() });
        }
        if !self.binary {
            return self.ascii_cells(n, size);
        }
        let flat = self.integers(size, "int", 4, "cell list entries")?;
        let mut offs = Vec::with_capacity(n + 1);
        let mut conn = Vec::with_capacity(size.saturating_sub(n));
        let mut k = 0usize;
        offs.push(0);
        for c in 0..n {
            let m = *flat.get(k).ok_or_else(|| self.lx.err(format!("cell list ends before cell {c} (of {n})")))?;
            if m < 0 || k + 1 + m as usize > flat.len() {
                return Err(self.lx.err(format!("cell {c} declares {m} nodes, beyond the declared list size {size}")));
            }
            conn.extend_from_slice(&flat[k + 1..k + 1 + m as usize]);
            offs.push(conn.len());
            k += 1 + m as usize;
        }
        if k != flat.len() {
            return Err(self
                .lx
                .err(format!("cell list size {size} does not match the {n} cells it holds ({k} entries)")));
        }
        Ok(CellList { offsets: offs, conn, lines: Vec::new() })
    }
}

impl Reader<'_> {
    /// ASCII `CELLS n size` list, cell by cell, so that an error names its line.
    fn ascii_cells(&mut self, n: usize, size: usize) -> IoResult<CellList> {
        let mut lines = Vec::with_capacity(n);
        let mut offs = Vec::with_capacity(n + 1);
        let mut conn = Vec::with_capacity(size.saturating_sub(n));
        offs.push(0);
        let mut used = 0usize;
        for c in 0..n {
            let m = self.lx.int("the node count of a cell")?;
            lines.push(self.lx.line());
            if m < 0 || used + 1 + m as usize > size {
                return Err(self.lx.err(format!("cell {c} declares {m} nodes, beyond the declared list size {size}")));
            }
            for _ in 0..m {
                // Indices are checked against the points once the cell's type is known
                // (a polyhedron's list also holds face sizes), at this cell's line.
                let v = self.lx.int("a point index")?;
                if v < 0 {
                    return Err(self.lx.err(format!("cell {c}: point index {v} is out of range (negative)")));
                }
                conn.push(v);
            }
            used += 1 + m as usize;
            offs.push(conn.len());
        }
        if used != size {
            return Err(self
                .lx
                .err(format!("cell list size {size} does not match the {n} cells it holds ({used} entries)")));
        }
        Ok(CellList { offsets: offs, conn, lines })
    }
}

/// Parses a legacy VTK file.
pub fn read(path: &Path, data: &[u8]) -> IoResult<IndexedMesh> {
    let mut lx = Lexer::new(path, data, None);
    let first = lx.rest_of_line();
    if !first.starts_with("# vtk DataFile") {
        return Err(lx.err(format!("expected '# vtk DataFile Version x.x', found '{}'", clip(first))));
    }
    lx.rest_of_line(); // title
    let fmt = lx.expect("ASCII or BINARY")?;
    let binary = match fmt.to_ascii_uppercase().as_str() {
        "ASCII" => false,
        "BINARY" => true,
        _ => return Err(lx.err(format!("expected ASCII or BINARY, found '{}'", clip(fmt)))),
    };
    lx.expect_word("DATASET")?;
    let ds = lx.expect("a dataset type")?;
    if ds != "UNSTRUCTURED_GRID" && ds != "POLYDATA" {
        return Err(IoError::unsupported(
            path,
            format!("dataset {ds} is not supported (UNSTRUCTURED_GRID or POLYDATA)"),
        ));
    }
    let mut r = Reader { lx, binary };
    let mut points: Vec<[f64; 3]> = Vec::new();
    let mut cells: Option<CellList> = None;
    let mut polys: Vec<CellList> = Vec::new();
    let mut types: Option<Vec<i64>> = None;
    let mut labels: Option<Vec<i64>> = None;
    let mut arrays: Vec<(String, Vec<i64>)> = Vec::new();
    let mut tuples = 0usize;
    let mut in_cell_data = false;
    while let Some(kw) = r.lx.token() {
        match kw {
            "POINTS" => {
                let n = r.lx.count("points", 3)?;
                let (t, s) = r.dtype()?;
                let v = r.numbers(n * 3, t, s, "point coordinates")?;
                points = v.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
            }
            "CELLS" => cells = Some(r.cells()?),
            "POLYGONS" | "TRIANGLE_STRIPS" => {
                let c = r.cells()?;
                if kw == "POLYGONS" {
                    polys.push(c);
                }
            }
            "VERTICES" | "LINES" => {
                r.cells()?;
            }
            "CELL_TYPES" => {
                let n = r.lx.count("cell types", if r.binary { 4 } else { 2 })?;
                types = Some(r.integers(n, "int", 4, "cell types")?);
            }
            "CELL_DATA" | "POINT_DATA" => {
                in_cell_data = kw == "CELL_DATA";
                tuples = r.lx.count("data tuples", 1)?;
            }
            "FIELD" if tuples == 0 => {
                r.attribute(kw, 0, &mut None)?;
            }
            _ => {
                let mut named = None;
                let l = r.attribute(kw, tuples, &mut named)?;
                if in_cell_data && l.is_some() && labels.is_none() {
                    labels = l;
                }
                if in_cell_data && let Some(a) = named {
                    arrays.push(a);
                }
            }
        }
    }
    let lx = &r.lx;
    let mut mesh = assemble(&|m| lx.err(m), points, cells, types, polys, labels)?;
    // Arrays qmesh wrote (one value per cell, no cell skipped) come back as they were.
    for (name, v) in arrays {
        if v.len() == mesh.nb_cells() && mesh.is_volume() {
            mesh.set_cell_array(&name, CellValues::Int(v.iter().map(|&x| x as i32).collect()));
        }
    }
    Ok(mesh)
}

/// Turns the parsed sections into an indexed mesh, checking every index and type.
pub(super) fn assemble(
    err: &dyn Fn(String) -> IoError,
    points: Vec<[f64; 3]>,
    cells: Option<CellList>,
    types: Option<Vec<i64>>,
    polys: Vec<CellList>,
    labels: Option<Vec<i64>>,
) -> IoResult<IndexedMesh> {
    let mut mesh = IndexedMesh::new();
    let np = points.len();
    mesh.points = points;
    let cell_lines = cells.as_ref().map_or(&[][..], |l| &l.lines[..]);
    let idx = |v: i64, c: usize| -> IoResult<u32> {
        if v < 0 || v as usize >= np {
            let e = err(format!("cell {c}: point index {v} is out of range (the file has {np} points)"));
            Err(match (e, cell_lines.get(c)) {
                (IoError::Parse { path, msg, .. }, Some(&line)) => {
                    IoError::Parse { path, at: Location::Line(line as usize), msg }
                }
                (e, _) => e,
            })
        } else {
            Ok(v as u32)
        }
    };
    let mut surface: Vec<(Vec<u32>, Option<u32>)> = Vec::new();
    let (mut lower, mut hex_as_tet, mut unsupported) = (0usize, 0usize, 0usize);
    if let Some(CellList { offsets: offs, conn, lines }) = &cells {
        let n = offs.len() - 1;
        let types = types.as_ref().ok_or_else(|| err("expected a CELL_TYPES section after CELLS".into()))?;
        if types.len() != n {
            return Err(err(format!("CELL_TYPES lists {} types for {n} cells", types.len())));
        }
        for c in 0..n {
            let raw = &conn[offs[c]..offs[c + 1]];
            let t = types[c];
            let kind = match (t, raw.len()) {
                (10, 8) => {
                    hex_as_tet += 1;
                    Some(CellKind::Hex)
                }
                (42, _) => Some(CellKind::Polyhedron),
                _ => CellKind::from_vtk_type(t),
            };
            match kind {
                Some(CellKind::Polyhedron) => {
                    let stream = polyhedron_stream(raw, c, &idx, err)?;
                    mesh.push_cell(CellKind::Polyhedron, &stream, label_of(&labels, c));
                    mesh.cell_lines.extend(lines.get(c));
                }
                Some(kind) => {
                    let need = kind.nodes().unwrap_or(0);
                    if raw.len() != need {
                        return Err(err(format!("cell {c}: VTK type {t} needs {need} points, found {}", raw.len())));
                    }
                    let nodes = raw.iter().map(|&v| idx(v, c)).collect::<IoResult<Vec<u32>>>()?;
                    mesh.push_cell(kind, &nodes, label_of(&labels, c));
                    mesh.cell_lines.extend(lines.get(c));
                }
                None => match t {
                    5 | 7 | 9 => {
                        surface.push((
                            raw.iter().map(|&v| idx(v, c)).collect::<IoResult<Vec<u32>>>()?,
                            lines.get(c).copied(),
                        ));
                    }
                    1..=4 => lower += 1,
                    _ => unsupported += 1,
                },
            }
        }
    }
    for CellList { offsets: offs, conn, lines } in &polys {
        for c in 0..offs.len() - 1 {
            let p = conn[offs[c]..offs[c + 1]].iter().map(|&v| idx(v, c)).collect::<IoResult<Vec<u32>>>()?;
            surface.push((p, lines.get(c).copied()));
        }
    }
    if hex_as_tet > 0 {
        mesh.warnings.push(format!("{hex_as_tet} cells declared type 10 (tetra) list 8 points: read as hexahedra"));
    }
    if unsupported > 0 {
        mesh.warnings.push(format!("skipped {unsupported} cells of unsupported (non-linear) VTK types"));
    }
    if mesh.is_volume() {
        lower += surface.len();
    } else {
        for (p, line) in &surface {
            mesh.push_polygon(p);
            mesh.poly_lines.extend(line);
        }
    }
    if lower > 0 {
        mesh.warnings.push(format!("skipped {lower} lower-dimensional cells (points, lines, polygons)"));
    }
    Ok(mesh)
}

fn label_of(labels: &Option<Vec<i64>>, c: usize) -> Option<i32> {
    labels.as_ref().and_then(|l| l.get(c)).map(|&v| v as i32)
}

fn polyhedron_stream(
    raw: &[i64],
    c: usize,
    idx: &dyn Fn(i64, usize) -> IoResult<u32>,
    err: &dyn Fn(String) -> IoError,
) -> IoResult<Vec<u32>> {
    let bad = || err(format!("cell {c}: malformed polyhedron face stream"));
    let nf = *raw.first().ok_or_else(bad)?;
    if nf < 4 {
        return Err(bad());
    }
    let mut out = vec![nf as u32];
    let mut k = 1usize;
    for _ in 0..nf {
        let n = *raw.get(k).ok_or_else(bad)?;
        if n < 3 || k + 1 + n as usize > raw.len() {
            return Err(bad());
        }
        out.push(n as u32);
        for &v in &raw[k + 1..k + 1 + n as usize] {
            out.push(idx(v, c)?);
        }
        k += 1 + n as usize;
    }
    if k != raw.len() {
        return Err(bad());
    }
    Ok(out)
}

/// Writes an UNSTRUCTURED_GRID (version 4.2 layout) in ASCII or big-endian BINARY,
/// with cell arrays `cell_type`, `scaled_jacobian` (volumes), `label` when the mesh
/// has labels, and the mesh's own arrays (`level`, …).
pub fn write(path: &Path, mesh: &IndexedMesh, binary: bool, w: &mut dyn Write) -> IoResult<()> {
    let io = |e| IoError::io(path, e);
    let cells: Vec<(u8, &[u32])> = if mesh.is_volume() {
        (0..mesh.nb_cells()).map(|i| (mesh.kinds[i].vtk_type(), mesh.cell(i).1)).collect()
    } else {
        (0..mesh.nb_polygons())
            .map(|i| {
                let p = mesh.polygon(i);
                (
                    match p.len() {
                        3 => 5,
                        4 => 9,
                        _ => 7,
                    },
                    p,
                )
            })
            .collect()
    };
    let mode = if binary { "BINARY" } else { "ASCII" };
    writeln!(w, "# vtk DataFile Version 4.2\nwritten by qmesh\n{mode}\nDATASET UNSTRUCTURED_GRID").map_err(io)?;
    writeln!(w, "POINTS {} double", mesh.points.len()).map_err(io)?;
    if binary {
        let mut buf = Vec::with_capacity(mesh.points.len() * 24);
        mesh.points.iter().flatten().for_each(|x| buf.extend_from_slice(&x.to_be_bytes()));
        w.write_all(&buf).map_err(io)?;
        writeln!(w).map_err(io)?;
    } else {
        for p in &mesh.points {
            writeln!(w, "{} {} {}", p[0], p[1], p[2]).map_err(io)?;
        }
    }
    let size: usize = cells.iter().map(|c| c.1.len() + 1).sum();
    writeln!(w, "CELLS {} {size}", cells.len()).map_err(io)?;
    let ints = |w: &mut dyn Write, v: &mut dyn Iterator<Item = i32>, per_line: bool| -> std::io::Result<()> {
        if binary {
            let buf: Vec<u8> = v.flat_map(|x| x.to_be_bytes()).collect();
            w.write_all(&buf)?;
            writeln!(w)
        } else {
            let mut first = true;
            for x in v {
                if !first {
                    w.write_all(if per_line { b" " } else { b"\n" })?;
                }
                write!(w, "{x}")?;
                first = false;
            }
            writeln!(w)
        }
    };
    if binary {
        let mut it = cells.iter().flat_map(|c| std::iter::once(c.1.len() as i32).chain(c.1.iter().map(|&v| v as i32)));
        ints(w, &mut it, false).map_err(io)?;
    } else {
        for c in &cells {
            write!(w, "{}", c.1.len()).map_err(io)?;
            for v in c.1 {
                write!(w, " {v}").map_err(io)?;
            }
            writeln!(w).map_err(io)?;
        }
    }
    writeln!(w, "CELL_TYPES {}", cells.len()).map_err(io)?;
    ints(w, &mut cells.iter().map(|c| c.0 as i32), false).map_err(io)?;
    // Cell arrays for ParaView: the VTK type of each cell, and labels when known.
    writeln!(w, "CELL_DATA {}\nSCALARS cell_type int 1\nLOOKUP_TABLE default", cells.len()).map_err(io)?;
    ints(w, &mut cells.iter().map(|c| c.0 as i32), false).map_err(io)?;
    if mesh.is_volume() && mesh.cell_array("scaled_jacobian").is_none() {
        writeln!(w, "SCALARS scaled_jacobian double 1\nLOOKUP_TABLE default").map_err(io)?;
        let q = crate::build::scaled_jacobians(mesh);
        if binary {
            let buf: Vec<u8> = q.iter().flat_map(|x| x.to_be_bytes()).collect();
            w.write_all(&buf).map_err(io)?;
            writeln!(w).map_err(io)?;
        } else {
            q.iter().try_for_each(|x| writeln!(w, "{x}")).map_err(io)?;
        }
    }
    if mesh.is_volume() && !mesh.labels.is_empty() {
        writeln!(w, "SCALARS label int 1\nLOOKUP_TABLE default").map_err(io)?;
        ints(w, &mut mesh.labels.iter().copied(), false).map_err(io)?;
    }
    for a in &mesh.cell_arrays {
        match &a.values {
            CellValues::Int(v) => {
                writeln!(w, "SCALARS {} int 1\nLOOKUP_TABLE default", a.name).map_err(io)?;
                ints(w, &mut v.iter().copied(), false).map_err(io)?;
            }
            CellValues::Float(v) => {
                writeln!(w, "SCALARS {} double 1\nLOOKUP_TABLE default", a.name).map_err(io)?;
                if binary {
                    let buf: Vec<u8> = v.iter().flat_map(|x| x.to_be_bytes()).collect();
                    w.write_all(&buf).map_err(io)?;
                    writeln!(w).map_err(io)?;
                } else {
                    v.iter().try_for_each(|x| writeln!(w, "{x}")).map_err(io)?;
                }
            }
        }
    }
    Ok(())
}
