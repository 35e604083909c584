//! PLY surfaces (ASCII, binary little- and big-endian): `vertex` x/y/z and `face`
//! vertex index lists; other elements and properties are skipped.

use std::path::Path;

use super::error::{IoError, IoResult};
use super::lexer::{Lexer, clip};
use crate::build::IndexedMesh;

#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Encoding {
    Ascii,
    Little,
    Big,
}

#[derive(Clone, Debug)]
enum Property {
    Scalar { name: String, size: usize, ty: String },
    List { name: String, count_size: usize, count_ty: String, size: usize, ty: String },
}

#[derive(Clone, Debug)]
struct Element {
    name: String,
    count: usize,
    props: Vec<Property>,
}

fn type_size(t: &str) -> Option<usize> {
    Some(match t {
        "char" | "uchar" | "int8" | "uint8" => 1,
        "short" | "ushort" | "int16" | "uint16" => 2,
        "int" | "uint" | "int32" | "uint32" | "float" | "float32" => 4,
        "double" | "float64" => 8,
        _ => return None,
    })
}

fn decode(b: &[u8], ty: &str, enc: Encoding) -> f64 {
    macro_rules! get {
        ($t:ty) => {{
            let a = b.try_into().unwrap();
            (if enc == Encoding::Big { <$t>::from_be_bytes(a) } else { <$t>::from_le_bytes(a) }) as f64
        }};
    }
    match ty {
        "char" | "int8" => b[0] as i8 as f64,
        "uchar" | "uint8" => b[0] as f64,
        "short" | "int16" => get!(i16),
        "ushort" | "uint16" => get!(u16),
        "int" | "int32" => get!(i32),
        "uint" | "uint32" => get!(u32),
        "float" | "float32" => get!(f32),
        _ => get!(f64),
    }
}

/// Reads one value of a property type, ASCII or binary.
fn value(lx: &mut Lexer<'_>, enc: Encoding, size: usize, ty: &str, what: &str) -> IoResult<f64> {
    let v = if enc == Encoding::Ascii { lx.parse::<f64>(what)? } else { decode(lx.bytes(size, what)?, ty, enc) };
    if v.is_finite() { Ok(v) } else { Err(lx.err_at_byte(format!("expected a finite {what}, found {v}"))) }
}

fn header(lx: &mut Lexer<'_>) -> IoResult<(Encoding, Vec<Element>)> {
    let magic = lx.rest_of_line();
    if magic.trim() != "ply" {
        return Err(lx.err(format!("expected 'ply' on the first line, found '{}'", clip(magic))));
    }
    let mut enc = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        if lx.remaining() == 0 {
            return Err(lx.err("expected 'end_header', found end of file"));
        }
        let line = lx.rest_of_line();
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.as_slice() {
            ["format", f, _] => {
                enc = Some(match *f {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::Little,
                    "binary_big_endian" => Encoding::Big,
                    _ => {
                        return Err(lx.err(format!("expected a PLY format (ascii, binary_…_endian), found '{f}'")));
                    }
                })
            }
            ["comment", ..] | ["obj_info", ..] | [] => {}
            ["element", name, n] => {
                let n: i64 =
                    n.parse().map_err(|_| lx.err(format!("expected an element count, found '{}'", clip(n))))?;
                let count = lx.check_count(n, &format!("'{name}' elements"), 1)?;
                elements.push(Element { name: name.to_string(), count, props: Vec::new() });
            }
            ["property", "list", ct, t, name] => {
                let el = elements.last_mut().ok_or_else(|| lx.err("expected 'element' before 'property'"))?;
                let (cs, s) = (type_size(ct), type_size(t));
                let (Some(count_size), Some(size)) = (cs, s) else {
                    return Err(lx.err(format!("expected PLY scalar types in list property, found '{ct} {t}'")));
                };
                el.props.push(Property::List {
                    name: name.to_string(),
                    count_size,
                    count_ty: ct.to_string(),
                    size,
                    ty: t.to_string(),
                });
            }
            ["property", t, name] => {
                let el = elements.last_mut().ok_or_else(|| lx.err("expected 'element' before 'property'"))?;
                let size =
                    type_size(t).ok_or_else(|| lx.err(format!("expected a PLY scalar type, found '{}'", clip(t))))?;
                el.props.push(Property::Scalar { name: name.to_string(), size, ty: t.to_string() });
            }
            ["end_header"] => break,
            _ => {
                return Err(lx.err(format!("expected a PLY header line, found '{}'", clip(line))));
            }
        }
    }
    let enc = enc.ok_or_else(|| lx.err("expected a 'format' line in the header"))?;
    Ok((enc, elements))
}

/// Parses a PLY file.
pub fn read(path: &Path, data: &[u8]) -> IoResult<IndexedMesh> {
    let mut lx = Lexer::new(path, data, None);
    let (enc, elements) = header(&mut lx)?;
    let mut mesh = IndexedMesh::new();
    let mut poly = Vec::new();
    let mut nv = 0usize;
    for el in &elements {
        let min = el.props.len().max(1);
        lx.check_count(el.count as i64, &format!("'{}' elements", el.name), min)?;
        for item in 0..el.count {
            let mut xyz = [0.0; 3];
            poly.clear();
            for p in &el.props {
                match p {
                    Property::Scalar { name, size, ty } => {
                        let v = value(&mut lx, enc, *size, ty, name)?;
                        match name.as_str() {
                            "x" => xyz[0] = v,
                            "y" => xyz[1] = v,
                            "z" => xyz[2] = v,
                            _ => {}
                        }
                    }
                    Property::List { name, count_size, count_ty, size, ty } => {
                        let n = value(&mut lx, enc, *count_size, count_ty, "list length")?;
                        let n =
                            lx.check_count(n as i64, "list entries", if enc == Encoding::Ascii { 2 } else { *size })?;
                        let is_face = el.name == "face" && (name == "vertex_indices" || name == "vertex_index");
                        for _ in 0..n {
                            let v = value(&mut lx, enc, *size, ty, "vertex index")?;
                            if is_face {
                                if v < 0.0 || v as usize >= nv {
                                    return Err(
                                        lx.err(format!("face {item}: vertex index {v} is out of range (0..{nv})"))
                                    );
                                }
                                poly.push(v as u32);
                            }
                        }
                    }
                }
            }
            if el.name == "vertex" {
                mesh.points.push(xyz);
            } else if el.name == "face" {
                if poly.len() < 3 {
                    return Err(
                        lx.err(format!("face {item}: expected at least 3 vertex indices, found {}", poly.len()))
                    );
                }
                mesh.push_polygon(&poly);
                if enc == Encoding::Ascii {
                    mesh.poly_lines.push(lx.line());
                }
            }
        }
        if el.name == "vertex" {
            nv = mesh.points.len();
        }
    }
    if mesh.nb_polygons() == 0 {
        return Err(IoError::unsupported(path, "the PLY file has no faces (point clouds are not meshes)"));
    }
    Ok(mesh)
}

/// Writes the mesh's points and polygons as PLY, ASCII or binary little-endian
/// (double coordinates, `uchar` counts and `int` indices; polygons of more than 255
/// vertices do not fit and are refused).
///
/// # Errors
/// An I/O error of `w`, or a polygon of more than 255 vertices.
pub fn write(path: &Path, mesh: &IndexedMesh, binary: bool, w: &mut dyn std::io::Write) -> IoResult<()> {
    let io = |e| IoError::io(path, e);
    if let Some(i) = (0..mesh.nb_polygons()).find(|&i| mesh.polygon(i).len() > 255) {
        return Err(IoError::unsupported(path, format!("polygon {i} has more than 255 vertices")));
    }
    let format = if binary { "binary_little_endian" } else { "ascii" };
    write!(
        w,
        "ply\nformat {format} 1.0\ncomment written by qmesh\nelement vertex {}\nproperty double x\n\
         property double y\nproperty double z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        mesh.points.len(),
        mesh.nb_polygons()
    )
    .map_err(io)?;
    for p in &mesh.points {
        if binary {
            for x in p {
                w.write_all(&x.to_le_bytes()).map_err(io)?;
            }
        } else {
            writeln!(w, "{} {} {}", p[0], p[1], p[2]).map_err(io)?;
        }
    }
    for i in 0..mesh.nb_polygons() {
        let p = mesh.polygon(i);
        if binary {
            w.write_all(&[p.len() as u8]).map_err(io)?;
            for &v in p {
                w.write_all(&(v as i32).to_le_bytes()).map_err(io)?;
            }
        } else {
            let ids: Vec<String> = p.iter().map(u32::to_string).collect();
            writeln!(w, "{} {}", p.len(), ids.join(" ")).map_err(io)?;
        }
    }
    Ok(())
}
