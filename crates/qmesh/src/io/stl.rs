//! STL surfaces, ASCII and binary; vertices are welded by exact coordinates.

use std::path::Path;

use rustc_hash::FxHashMap;

use super::error::{IoError, IoResult, Location};
use super::lexer::Lexer;
use crate::build::IndexedMesh;

/// Merges identical coordinates into one vertex.
#[derive(Default)]
struct Welder {
    ids: FxHashMap<[u64; 3], u32>,
    mesh: IndexedMesh,
}

impl Welder {
    fn vertex(&mut self, p: [f64; 3]) -> u32 {
        // +0.0 and -0.0 weld together.
        let key = p.map(|x| (if x == 0.0 { 0.0 } else { x }).to_bits());
        let points = &mut self.mesh.points;
        *self.ids.entry(key).or_insert_with(|| {
            points.push(p);
            (points.len() - 1) as u32
        })
    }

    fn triangle(&mut self, t: [[f64; 3]; 3]) {
        let ids = t.map(|p| self.vertex(p));
        self.mesh.push_polygon(&ids);
    }
}

/// Parses an STL file (binary when the size matches the 84 + 50·n layout and the file
/// does not start with `solid` followed by `facet`).
pub fn read(path: &Path, data: &[u8]) -> IoResult<IndexedMesh> {
    let mut w = Welder { mesh: IndexedMesh::new(), ..Default::default() };
    let looks_ascii = data.starts_with(b"solid") && data.windows(5).take(1024).any(|x| x == b"facet");
    if looks_ascii {
        read_ascii(path, data, &mut w)?;
    } else {
        read_binary(path, data, &mut w)?;
    }
    if w.mesh.nb_polygons() == 0 {
        return Err(IoError::Parse {
            path: path.into(),
            at: Location::Byte(0),
            msg: "expected at least one facet".into(),
        });
    }
    Ok(w.mesh)
}

fn read_ascii(path: &Path, data: &[u8], w: &mut Welder) -> IoResult<()> {
    let mut lx = Lexer::new(path, data, None);
    lx.expect_word("solid")?;
    lx.rest_of_line();
    loop {
        let t = lx.expect("'facet' or 'endsolid'")?;
        match t {
            "endsolid" => return Ok(()),
            "facet" => {
                lx.expect_word("normal")?;
                // The normal is recomputed from the vertices; a malformed one is ignored.
                let _ = lx.point();
                lx.expect_word("outer")?;
                lx.expect_word("loop")?;
                let mut tri = [[0.0; 3]; 3];
                for p in tri.iter_mut() {
                    lx.expect_word("vertex")?;
                    *p = lx.point()?;
                }
                lx.expect_word("endloop")?;
                lx.expect_word("endfacet")?;
                w.triangle(tri);
            }
            other => {
                return Err(lx.err(format!("expected 'facet' or 'endsolid', found '{}'", super::lexer::clip(other))));
            }
        }
    }
}

fn read_binary(path: &Path, data: &[u8], w: &mut Welder) -> IoResult<()> {
    let err = |at: usize, msg: String| IoError::Parse { path: path.into(), at: Location::Byte(at), msg };
    if data.len() < 84 {
        return Err(err(data.len(), format!("expected a binary STL header of 84 bytes, the file has {}", data.len())));
    }
    let n = u32::from_le_bytes(data[80..84].try_into().unwrap()) as usize;
    let need = 84 + 50 * n as u128;
    if (data.len() as u128) < need {
        return Err(err(
            84,
            format!("header declares {n} triangles ({need} bytes) but the file has {} bytes", data.len()),
        ));
    }
    for k in 0..n {
        let rec = &data[84 + 50 * k..84 + 50 * (k + 1)];
        let f = |i: usize| f32::from_le_bytes(rec[i * 4..i * 4 + 4].try_into().unwrap()) as f64;
        let tri = [[f(3), f(4), f(5)], [f(6), f(7), f(8)], [f(9), f(10), f(11)]];
        if tri.iter().flatten().any(|x| !x.is_finite()) {
            return Err(err(84 + 50 * k, format!("triangle {k}: expected finite coordinates")));
        }
        w.triangle(tri);
    }
    Ok(())
}

/// The triangles of the mesh's polygons (fans from each polygon's first vertex).
fn triangles(mesh: &IndexedMesh) -> impl Iterator<Item = [[f64; 3]; 3]> + '_ {
    (0..mesh.nb_polygons()).flat_map(move |i| {
        let p = mesh.polygon(i);
        (1..p.len().saturating_sub(1)).map(move |k| [p[0], p[k], p[k + 1]].map(|v| mesh.points[v as usize]))
    })
}

/// The unit normal of a triangle (zero when degenerate).
fn normal(t: &[[f64; 3]; 3]) -> [f64; 3] {
    use crate::geom::{cross, sub};
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 { n.map(|x| x / len) } else { [0.0; 3] }
}

/// Writes the mesh's polygons as STL triangles (fan-triangulated), ASCII or binary
/// (little-endian, 32-bit floats: coordinates are rounded to single precision, as the
/// format holds).
///
/// # Errors
/// An I/O error of `w`.
pub fn write(path: &Path, mesh: &IndexedMesh, binary: bool, w: &mut dyn std::io::Write) -> IoResult<()> {
    let io = |e| IoError::io(path, e);
    if binary {
        let mut header = [0u8; 80];
        let text = b"binary STL written by qmesh";
        header[..text.len()].copy_from_slice(text);
        w.write_all(&header).map_err(io)?;
        let n = u32::try_from(triangles(mesh).count())
            .map_err(|_| IoError::unsupported(path, "more than 2^32 triangles for binary STL"))?;
        w.write_all(&n.to_le_bytes()).map_err(io)?;
        for t in triangles(mesh) {
            for v in std::iter::once(normal(&t)).chain(t) {
                for x in v {
                    w.write_all(&(x as f32).to_le_bytes()).map_err(io)?;
                }
            }
            w.write_all(&[0, 0]).map_err(io)?;
        }
        return Ok(());
    }
    writeln!(w, "solid qmesh").map_err(io)?;
    for t in triangles(mesh) {
        let n = normal(&t);
        writeln!(w, "  facet normal {} {} {}\n    outer loop", n[0], n[1], n[2]).map_err(io)?;
        for p in t {
            writeln!(w, "      vertex {} {} {}", p[0], p[1], p[2]).map_err(io)?;
        }
        writeln!(w, "    endloop\n  endfacet").map_err(io)?;
    }
    writeln!(w, "endsolid qmesh").map_err(io)
}
