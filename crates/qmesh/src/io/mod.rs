//! File formats: one file per format, format detection, atomic writes (GUIDE §1, §3).
//!
//! Readers take the whole file as bytes and return an [`IndexedMesh`] (or a map for
//! `.moka`); every error names the file, the line or byte offset, and what was
//! expected. Declared counts are checked against the bytes left before allocating.

mod atomic;
mod cgal_lcc;
mod error;
mod gmsh;
mod lexer;
mod medit;
mod moka;
mod obj;
mod off;
mod ply;
mod stl;
mod vtk_legacy;
mod vtu;
mod vtu_headers;

use std::path::Path;
use std::time::Instant;

pub use atomic::{temp_path, write_atomically};
pub use error::{IoError, IoResult, Location};

use crate::build::{
    BuildError, BuildOptions, BuildReport, IndexedMesh, Subject, boundary_polygons, build_map, extract,
};
use crate::cmap::CMap3;

/// A mesh file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Vtk,
    Vtu,
    Medit,
    Msh,
    Off,
    Obj,
    Stl,
    Ply,
    Moka,
}

impl Format {
    pub const ALL: [Format; 9] = [
        Format::Vtk,
        Format::Vtu,
        Format::Medit,
        Format::Msh,
        Format::Off,
        Format::Obj,
        Format::Stl,
        Format::Ply,
        Format::Moka,
    ];

    /// The format named by a file extension or a `--format` value.
    pub fn from_name(s: &str) -> Option<Format> {
        Some(match s.to_ascii_lowercase().as_str() {
            "vtk" => Format::Vtk,
            "vtu" => Format::Vtu,
            "mesh" | "medit" => Format::Medit,
            "msh" | "gmsh" => Format::Msh,
            "off" => Format::Off,
            "obj" => Format::Obj,
            "stl" => Format::Stl,
            "ply" => Format::Ply,
            "moka" => Format::Moka,
            _ => return None,
        })
    }

    /// The format of a path, from its extension.
    pub fn from_path(path: &Path) -> Option<Format> {
        path.extension().and_then(|e| e.to_str()).and_then(Format::from_name)
    }

    pub fn name(self) -> &'static str {
        match self {
            Format::Vtk => "vtk",
            Format::Vtu => "vtu",
            Format::Medit => "mesh",
            Format::Msh => "msh",
            Format::Off => "off",
            Format::Obj => "obj",
            Format::Stl => "stl",
            Format::Ply => "ply",
            Format::Moka => "moka",
        }
    }

    /// Whether qmesh can write this format (all of them).
    pub fn writable(self) -> bool {
        true
    }

    /// Whether the format holds surfaces only: a volume mesh written to it is written
    /// as its boundary surface.
    pub fn is_surface(self) -> bool {
        matches!(self, Format::Off | Format::Obj | Format::Stl | Format::Ply)
    }
}

/// What a reader returns: indexed cells, or a map for formats that store one.
#[derive(Debug)]
pub enum Loaded {
    Indexed(IndexedMesh),
    Map(CMap3),
}

/// Resolves the format of `path` (`forced` wins over the extension).
pub fn resolve_format(path: &Path, forced: Option<Format>) -> IoResult<Format> {
    forced.or_else(|| Format::from_path(path)).ok_or_else(|| {
        IoError::unsupported(
            path,
            "unknown file extension; use --format (vtk, vtu, mesh, msh, off, obj, stl, ply, moka)",
        )
    })
}

/// Parses bytes already in memory.
pub fn parse(path: &Path, data: &[u8], format: Format) -> IoResult<Loaded> {
    Ok(match format {
        Format::Vtk => Loaded::Indexed(vtk_legacy::read(path, data)?),
        Format::Vtu => Loaded::Indexed(vtu::read(path, data)?),
        // The authors' marching-cubes patterns use CGAL's polyhedral text under `.mesh`.
        Format::Medit if cgal_lcc::looks_like(data) => Loaded::Indexed(cgal_lcc::read(path, data)?),
        Format::Medit => Loaded::Indexed(medit::read(path, data)?),
        Format::Msh => Loaded::Indexed(gmsh::read(path, data)?),
        Format::Off => Loaded::Indexed(off::read(path, data)?),
        Format::Obj => Loaded::Indexed(obj::read(path, data)?),
        Format::Stl => Loaded::Indexed(stl::read(path, data)?),
        Format::Ply => Loaded::Indexed(ply::read(path, data)?),
        Format::Moka => Loaded::Map(moka::read(path, data)?),
    })
}

/// Reads a surface for the applications that need one (octree subdivision, marching
/// cubes): the polygons of a surface file, or the boundary of a volume mesh.
///
/// # Errors
/// As [`read`], plus a volume mesh that does not build.
pub fn read_surface(path: &Path, forced: Option<Format>) -> IoResult<IndexedMesh> {
    let map = match read(path, forced)? {
        Loaded::Indexed(mesh) if !mesh.is_volume() => return Ok(mesh),
        Loaded::Indexed(mesh) => {
            crate::build::build_map(mesh, &BuildOptions::default())
                .map_err(|cause| IoError::Build { path: path.into(), cause })?
                .0
        }
        Loaded::Map(map) => map,
    };
    Ok(crate::build::boundary_polygons(&map))
}

/// Writes a map as `.moka` (atomically) with the darts of `flags` marked: patterns
/// whose flags are not geometric (marching cubes) keep them this way.
pub fn write_moka_with_flags(path: &Path, map: &CMap3, flags: crate::cmap::Mark) -> IoResult<()> {
    write_atomically(path, |w| moka::write(path, map, Some(flags), w))
}

/// Reads a `.moka` file with the darts its marks flag (see `moka::read_with_flags`).
pub fn read_moka_with_flags(path: &Path) -> IoResult<(CMap3, Vec<crate::cmap::Dart>)> {
    let data = std::fs::read(path).map_err(|e| IoError::io(path, e))?;
    moka::read_with_flags(path, &data)
}

/// Reads a file.
///
/// # Errors
/// A folder or a missing file, an unknown format, or what the format's reader finds.
pub fn read(path: &Path, forced: Option<Format>) -> IoResult<Loaded> {
    // A folder is told from the failure only (no `stat` per file read).
    let folder = || IoError::unsupported(path, "this is a folder, not a mesh file");
    let format = resolve_format(path, forced).map_err(|e| if path.is_dir() { folder() } else { e })?;
    let data = std::fs::read(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::IsADirectory => folder(),
        _ => IoError::io(path, e),
    })?;
    parse(path, &data, format)
}

/// A map loaded from a file, with what the reader and builder reported and timings.
#[derive(Debug)]
pub struct LoadedMap {
    pub map: CMap3,
    pub report: BuildReport,
    pub warnings: Vec<String>,
    pub read_seconds: f64,
    pub build_seconds: f64,
    /// The file's per-cell arrays (`level`, `pattern_id`), in file cell order — which
    /// is the map's volume order, as the builder creates one volume per cell in order.
    pub cell_arrays: Vec<crate::build::CellArray>,
}

/// Reads a file and builds its map.
pub fn load_map(path: &Path, forced: Option<Format>, opts: &BuildOptions) -> IoResult<LoadedMap> {
    let t0 = Instant::now();
    let loaded = read(path, forced)?;
    let read_seconds = t0.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let (map, report, warnings, cell_arrays) = match loaded {
        Loaded::Map(m) => (m, BuildReport::default(), Vec::new(), Vec::new()),
        Loaded::Indexed(mut mesh) => {
            let warnings = std::mem::take(&mut mesh.warnings);
            let arrays = std::mem::take(&mut mesh.cell_arrays);
            let lines = (std::mem::take(&mut mesh.cell_lines), std::mem::take(&mut mesh.poly_lines));
            let (m, r) = build_map(mesh, opts).map_err(|cause| locate_build_error(path, cause, &lines))?;
            (m, r, warnings, arrays)
        }
    };
    let build_seconds = t1.elapsed().as_secs_f64();
    Ok(LoadedMap { map, report, warnings, read_seconds, build_seconds, cell_arrays })
}

/// A builder error, pointed at the source line of the cell it names last when the
/// reader recorded lines (the other named cells' lines are listed in the message).
fn locate_build_error(path: &Path, cause: BuildError, (cells, polys): &(Vec<u32>, Vec<u32>)) -> IoError {
    let line_of = |s: &Subject| match *s {
        Subject::Cell(c) => cells.get(c).copied(),
        Subject::Polygon(p) => polys.get(p).copied(),
    };
    let lines: Vec<u32> = cause.subjects().iter().filter_map(line_of).collect();
    match lines.last() {
        Some(&at) => {
            let also = if lines.len() > 1 {
                format!(" (lines {})", lines.iter().map(|l| l.to_string()).collect::<Vec<_>>().join(", "))
            } else {
                String::new()
            };
            IoError::Parse { path: path.into(), at: Location::Line(at as usize), msg: format!("{cause}{also}") }
        }
        None => IoError::Build { path: path.into(), cause },
    }
}

/// Options of writers.
#[derive(Clone, Copy, Debug, Default)]
pub struct WriteOptions {
    /// Binary instead of ASCII (legacy VTK, STL, PLY).
    pub binary: bool,
}

/// Writes indexed cells (atomically). A surface format (OFF, OBJ, STL, PLY) gets the
/// boundary surface of volume cells ([`IndexedMesh::boundary_surface`]), never an
/// empty file.
///
/// # Errors
/// An I/O error, `.moka` (a map format: use [`write_map`]), or what the format cannot
/// hold (a polygon of more than 255 vertices in PLY).
pub fn write_indexed(path: &Path, mesh: &IndexedMesh, format: Format, opts: &WriteOptions) -> IoResult<()> {
    let surface;
    let mesh = if format.is_surface() && mesh.is_volume() {
        surface = mesh.boundary_surface();
        &surface
    } else {
        mesh
    };
    write_atomically(path, |w| match format {
        Format::Vtk => vtk_legacy::write(path, mesh, opts.binary, w),
        Format::Vtu => vtu::write(path, mesh, w),
        Format::Medit => medit::write(path, mesh, w),
        Format::Msh => gmsh::write(path, mesh, w),
        Format::Off => off::write(path, mesh, w),
        Format::Obj => obj::write(path, mesh, w),
        Format::Stl => stl::write(path, mesh, opts.binary, w),
        Format::Ply => ply::write(path, mesh, opts.binary, w),
        Format::Moka => Err(IoError::unsupported(path, "a .moka file holds a map: write the map, not indexed cells")),
    })
}

/// Writes a map (atomically): volume formats get its cells; OFF/OBJ get its boundary
/// surface (or its faces for a surface map); `.moka` gets the map itself.
pub fn write_map(path: &Path, map: &CMap3, forced: Option<Format>, opts: &WriteOptions) -> IoResult<()> {
    write_map_with_arrays(path, map, &[], forced, opts)
}

/// As [`write_map`], with per-volume arrays (in the map's volume order) attached to the
/// cells of volume formats; arrays of another length are left out.
///
/// # Errors
/// An unknown format, or an I/O error.
pub fn write_map_with_arrays(
    path: &Path,
    map: &CMap3,
    arrays: &[crate::build::CellArray],
    forced: Option<Format>,
    opts: &WriteOptions,
) -> IoResult<()> {
    let format = resolve_format(path, forced)?;
    match format {
        Format::Moka => write_atomically(path, |w| moka::write(path, map, None, w)),
        _ => write_indexed(path, &indexed_for(map, arrays, format, false), format, opts),
    }
}

/// What a file of `format` (not `.moka`) holds of `map`: the boundary surface of a
/// volume map for surface formats, else its cells (or its faces, for a surface map)
/// with the per-volume `arrays` of the right length; points no cell uses are kept with
/// `keep_unused_points`, else dropped.
pub fn indexed_for(
    map: &CMap3,
    arrays: &[crate::build::CellArray],
    format: Format,
    keep_unused_points: bool,
) -> IndexedMesh {
    if format.is_surface() && map.dimension() == 3 {
        return boundary_polygons(map);
    }
    let mut cells = if keep_unused_points { crate::build::extract_all_points(map).0 } else { extract(map).0 };
    let n = if cells.is_volume() { cells.nb_cells() } else { usize::MAX };
    for a in arrays.iter().filter(|a| a.values.len() == n) {
        cells.set_cell_array(&a.name, a.values.clone());
    }
    cells
}
