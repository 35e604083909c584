//! Gmsh `.msh` ASCII: read versions 2.2 and 4.1, write 4.1. Linear cells use VTK node
//! order (GUIDE §3); the elementary entity tag of a volume element is its label.

use std::io::Write;
use std::path::Path;

use rustc_hash::FxHashMap;

use super::error::{IoError, IoResult};
use super::lexer::{Lexer, clip};
use crate::build::{CellKind, IndexedMesh};

/// Gmsh element type → (nodes, volume kind or None for a surface polygon, dimension).
fn element(t: i64) -> Option<(usize, Option<CellKind>, u8)> {
    Some(match t {
        15 => (1, None, 0),
        1 => (2, None, 1),
        2 => (3, None, 2),
        3 => (4, None, 2),
        4 => (4, Some(CellKind::Tet), 3),
        5 => (8, Some(CellKind::Hex), 3),
        6 => (6, Some(CellKind::Prism), 3),
        7 => (5, Some(CellKind::Pyramid), 3),
        _ => return None,
    })
}

fn gmsh_type(k: CellKind) -> Option<u8> {
    Some(match k {
        CellKind::Tet => 4,
        CellKind::Hex => 5,
        CellKind::Prism => 6,
        CellKind::Pyramid => 7,
        CellKind::Polyhedron => return None,
    })
}

/// Node tags → dense indices (tags may be sparse).
struct NodeTags {
    map: FxHashMap<i64, u32>,
}

impl NodeTags {
    fn get(&self, lx: &Lexer<'_>, tag: i64) -> IoResult<u32> {
        self.map.get(&tag).copied().ok_or_else(|| lx.err(format!("node tag {tag} is not defined in $Nodes")))
    }
}

/// Collected elements before choosing the highest dimension.
#[derive(Default)]
struct Elements {
    volume: Vec<(CellKind, Vec<u32>, i32, u32)>,
    surface: Vec<(Vec<u32>, u32)>,
    lower: usize,
    unsupported: usize,
}

impl Elements {
    fn push(&mut self, t: i64, nodes: Vec<u32>, label: i32, line: u32) {
        match element(t) {
            Some((_, Some(k), _)) => self.volume.push((k, nodes, label, line)),
            Some((_, None, 2)) => self.surface.push((nodes, line)),
            Some(_) => self.lower += 1,
            None => self.unsupported += 1,
        }
    }
}

/// Parses a gmsh mesh (ASCII 2.2 or 4.1).
pub fn read(path: &Path, data: &[u8]) -> IoResult<IndexedMesh> {
    let mut lx = Lexer::new(path, data, None);
    lx.expect_word("$MeshFormat")?;
    let version = lx.expect("a format version (2.2 or 4.1)")?;
    let file_type: i64 = lx.parse("the file type (0 = ASCII)")?;
    let _dsize: i64 = lx.parse("the data size")?;
    if file_type != 0 {
        return Err(IoError::unsupported(path, "binary .msh files are not supported yet; save as ASCII"));
    }
    let v4 = match version {
        "2.2" | "2.1" | "2" | "2.0" => false,
        "4.1" => true,
        _ => {
            return Err(IoError::unsupported(
                path,
                format!("MSH version {} is not supported (2.2 or 4.1)", clip(version)),
            ));
        }
    };
    lx.expect_word("$EndMeshFormat")?;
    let mut mesh = IndexedMesh::new();
    let mut tags = NodeTags { map: FxHashMap::default() };
    let mut els = Elements::default();
    while let Some(section) = lx.token() {
        match section {
            "$Nodes" if v4 => nodes_v4(&mut lx, &mut mesh, &mut tags)?,
            "$Nodes" => nodes_v2(&mut lx, &mut mesh, &mut tags)?,
            "$Elements" if v4 => elements_v4(&mut lx, &tags, &mut els)?,
            "$Elements" => elements_v2(&mut lx, &tags, &mut els)?,
            s if s.starts_with('$') && !s.starts_with("$End") => {
                // Skip $PhysicalNames, $Entities, $NodeData… up to the matching end tag.
                let end = format!("$End{}", &s[1..]);
                loop {
                    match lx.token() {
                        Some(t) if t == end => break,
                        Some(_) => {}
                        None => return Err(lx.err(format!("expected '{end}', found end of file"))),
                    }
                }
            }
            other => {
                return Err(lx.err(format!("expected a section such as $Nodes, found '{}'", clip(other))));
            }
        }
    }
    if els.volume.is_empty() {
        for (p, line) in &els.surface {
            mesh.push_polygon(p);
            mesh.poly_lines.push(*line);
        }
    } else {
        for (k, n, l, line) in &els.volume {
            mesh.push_cell(*k, n, Some(*l));
            mesh.cell_lines.push(*line);
        }
        els.lower += els.surface.len();
    }
    if els.lower > 0 {
        mesh.warnings.push(format!("skipped {} lower-dimensional elements", els.lower));
    }
    if els.unsupported > 0 {
        mesh.warnings.push(format!("skipped {} elements of unsupported (high-order) types", els.unsupported));
    }
    Ok(mesh)
}

fn nodes_v2(lx: &mut Lexer<'_>, mesh: &mut IndexedMesh, tags: &mut NodeTags) -> IoResult<()> {
    let n = lx.count("nodes", 8)?;
    mesh.points.reserve(n);
    for _ in 0..n {
        let tag: i64 = lx.parse("a node tag")?;
        let p = lx.point()?;
        if tags.map.insert(tag, mesh.points.len() as u32).is_some() {
            return Err(lx.err(format!("node tag {tag} is defined twice")));
        }
        mesh.points.push(p);
    }
    lx.expect_word("$EndNodes")
}

fn nodes_v4(lx: &mut Lexer<'_>, mesh: &mut IndexedMesh, tags: &mut NodeTags) -> IoResult<()> {
    let blocks = lx.count("node blocks", 8)?;
    let total = lx.count("nodes", 8)?;
    let _min: i64 = lx.parse("the minimum node tag")?;
    let _max: i64 = lx.parse("the maximum node tag")?;
    mesh.points.reserve(total);
    for _ in 0..blocks {
        let _dim: i64 = lx.parse("an entity dimension")?;
        let _tag: i64 = lx.parse("an entity tag")?;
        let parametric: i64 = lx.parse("the parametric flag")?;
        let n = lx.count("nodes in the block", 8)?;
        if parametric != 0 {
            return Err(IoError::unsupported(lx.path(), "parametric nodes are not supported"));
        }
        let first = mesh.points.len() as u32;
        let mut block_tags = Vec::with_capacity(n);
        for _ in 0..n {
            block_tags.push(lx.parse::<i64>("a node tag")?);
        }
        for (k, &tag) in block_tags.iter().enumerate() {
            mesh.points.push(lx.point()?);
            if tags.map.insert(tag, first + k as u32).is_some() {
                return Err(lx.err(format!("node tag {tag} is defined twice")));
            }
        }
    }
    if mesh.points.len() != total {
        return Err(lx.err(format!("$Nodes declares {total} nodes but its blocks hold {}", mesh.points.len())));
    }
    lx.expect_word("$EndNodes")
}

fn elements_v2(lx: &mut Lexer<'_>, tags: &NodeTags, els: &mut Elements) -> IoResult<()> {
    let n = lx.count("elements", 8)?;
    for _ in 0..n {
        let _id: i64 = lx.parse("an element tag")?;
        let t: i64 = lx.parse("an element type")?;
        let ntags = lx.count("element tags", 2)?;
        let mut etags = Vec::with_capacity(ntags);
        for _ in 0..ntags {
            etags.push(lx.parse::<i64>("an element tag value")?);
        }
        let (k, ..) =
            element(t).ok_or_else(|| lx.err(format!("element type {t} is not supported (linear types 1-7, 15)")))?;
        let nodes = node_list(lx, tags, t, k)?;
        let label = etags.get(1).or(etags.first()).copied().unwrap_or(0) as i32;
        els.push(t, nodes, label, lx.line());
    }
    lx.expect_word("$EndElements")
}

/// The `k` node tags of an element of type `t`, all on the element's line (an element
/// line with too few nodes is reported as such, not read on into the next line).
fn node_list(lx: &mut Lexer<'_>, tags: &NodeTags, t: i64, k: usize) -> IoResult<Vec<u32>> {
    let line = lx.line();
    let path = lx.path();
    let mut out = Vec::with_capacity(k);
    for found in 0..k {
        let short = || IoError::Parse {
            path: path.into(),
            at: super::error::Location::Line(line as usize),
            msg: format!("an element of type {t} ({}) needs {k} nodes, this one has {found}", type_name(t)),
        };
        match lx.peek() {
            None => return Err(short()),
            Some(_) => {
                let tag = lx.int("a node tag")?;
                if lx.line() != line {
                    return Err(short());
                }
                out.push(tags.get(lx, tag)?);
            }
        }
    }
    Ok(out)
}

/// A person's name for a gmsh element type.
fn type_name(t: i64) -> &'static str {
    match t {
        15 => "point",
        1 => "line",
        2 => "triangle",
        3 => "quadrangle",
        4 => "tetrahedron",
        5 => "hexahedron",
        6 => "prism",
        7 => "pyramid",
        _ => "unsupported",
    }
}

fn elements_v4(lx: &mut Lexer<'_>, tags: &NodeTags, els: &mut Elements) -> IoResult<()> {
    let blocks = lx.count("element blocks", 8)?;
    let _total = lx.count("elements", 4)?;
    let _min: i64 = lx.parse("the minimum element tag")?;
    let _max: i64 = lx.parse("the maximum element tag")?;
    for _ in 0..blocks {
        let _dim: i64 = lx.parse("an entity dimension")?;
        let entity: i64 = lx.parse("an entity tag")?;
        let t: i64 = lx.parse("an element type")?;
        let n = lx.count("elements in the block", 4)?;
        let (k, ..) =
            element(t).ok_or_else(|| lx.err(format!("element type {t} is not supported (linear types 1-7, 15)")))?;
        for _ in 0..n {
            let _id: i64 = lx.parse("an element tag")?;
            let nodes = node_list(lx, tags, t, k)?;
            els.push(t, nodes, entity as i32, lx.line());
        }
    }
    lx.expect_word("$EndElements")
}

/// Identifies one element block: entity dimension, entity tag, element type.
type BlockKey = (u8, i32, u8);

/// Writes a gmsh 4.1 ASCII mesh: one node block, one element block per (kind, label).
///
/// # Errors
/// Polyhedra cannot be stored in .msh files.
pub fn write(path: &Path, mesh: &IndexedMesh, w: &mut dyn Write) -> IoResult<()> {
    let io = |e| IoError::io(path, e);
    // (entity dimension, entity tag, element type) → elements of that block.
    let mut blocks: Vec<(BlockKey, Vec<&[u32]>)> = Vec::new();
    let mut index: FxHashMap<BlockKey, usize> = FxHashMap::default();
    let mut add = |key: BlockKey| -> usize {
        *index.entry(key).or_insert_with(|| {
            blocks.push((key, Vec::new()));
            blocks.len() - 1
        })
    };
    let mut members: Vec<(usize, &[u32])> = Vec::new();
    for i in 0..mesh.nb_cells() {
        let (k, nodes) = mesh.cell(i);
        let t = gmsh_type(k)
            .ok_or_else(|| IoError::unsupported(path, "gmsh .msh has no polyhedron cells; write VTK instead"))?;
        members.push((add((3, mesh.label(i).unwrap_or(1).max(1), t)), nodes));
    }
    for i in 0..mesh.nb_polygons() {
        let p = mesh.polygon(i);
        let t = match p.len() {
            3 => 2,
            4 => 3,
            n => {
                return Err(IoError::unsupported(path, format!("gmsh .msh stores triangles and quads, not {n}-gons")));
            }
        };
        members.push((add((2, 1, t)), p));
    }
    for (b, nodes) in members {
        blocks[b].1.push(nodes);
    }
    let mut entities: Vec<(u8, i32)> = blocks.iter().map(|((d, e, _), _)| (*d, *e)).collect();
    entities.sort_unstable();
    entities.dedup();
    let count = |d: u8| entities.iter().filter(|e| e.0 == d).count();
    writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Entities\n0 0 {} {}", count(2), count(3)).map_err(io)?;
    for &(_, e) in &entities {
        // tag, bounding box (unused), no physical tags, no bounding entities
        writeln!(w, "{e} 0 0 0 0 0 0 0 0").map_err(io)?;
    }
    writeln!(w, "$EndEntities").map_err(io)?;
    let np = mesh.points.len();
    let (nd, ne) = entities.first().copied().unwrap_or((3, 1));
    writeln!(w, "$Nodes\n1 {np} 1 {np}\n{nd} {ne} 0 {np}").map_err(io)?;
    for i in 1..=np {
        writeln!(w, "{i}").map_err(io)?;
    }
    for p in &mesh.points {
        writeln!(w, "{} {} {}", p[0], p[1], p[2]).map_err(io)?;
    }
    let total: usize = blocks.iter().map(|b| b.1.len()).sum();
    writeln!(w, "$EndNodes\n$Elements\n{} {total} 1 {total}", blocks.len()).map_err(io)?;
    let mut tag = 1usize;
    for ((d, e, t), cells) in &blocks {
        writeln!(w, "{d} {e} {t} {}", cells.len()).map_err(io)?;
        for c in cells {
            write!(w, "{tag}").map_err(io)?;
            for v in c.iter() {
                write!(w, " {}", v + 1).map_err(io)?;
            }
            writeln!(w).map_err(io)?;
            tag += 1;
        }
    }
    writeln!(w, "$EndElements").map_err(io)
}
