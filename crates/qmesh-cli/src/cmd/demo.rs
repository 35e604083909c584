//! `qmesh demo [-o DIR]`: a tour of the 2022 applications on built-in inputs (a torus
//! surface, a scalar field, hex and tet grids), writing each result and a PNG of it.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::Result;
use qmesh::apps::{
    GeneratedKind, McFlags, RootShape, SubdivideOptions, conformal, generated_pattern_set, marching_cubes_field,
    marching_cubes_surface, mc_pattern_set, subdivide, tet_to_hex, triangulate,
};
use qmesh::build::{BuildOptions, IndexedMesh, build_surface_map, build_volume_map, extract};
use qmesh::generate::{hex_grid, tet_grid, torus_surface};
use qmesh::geom::TriangleBvh;
use qmesh::io::{Format, IoError, WriteOptions, write_atomically, write_indexed};
use qmesh::pattern::FlagRule;
use qmesh::render::{Clip, ColorBy, RenderOptions, render_titled};
use qmesh::replace::{ReplaceOptions, query_replace};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Folder for the files the demo writes.
    #[arg(short, long, default_value = "qmesh-demo")]
    pub output: PathBuf,
}

/// Writes `mesh` as `name` and its picture as `name`.png; prints one line.
fn save(dir: &Path, name: &str, mesh: &IndexedMesh, what: &str, picture: RenderOptions) -> Result<()> {
    let file = dir.join(name);
    let format = Format::from_path(&file).unwrap_or(Format::Vtk);
    write_indexed(&file, mesh, format, &WriteOptions::default())?;
    let png = file.with_extension("png");
    // The picture font is ASCII.
    let title = format!("{name}: {what}").replace('χ', "chi").replace('³', "^3");
    let (canvas, _) = render_titled(mesh, &picture, Some(&title));
    write_atomically(&png, |w| canvas.write_png(w).map_err(|e| IoError::io(&png, e)))?;
    println!("  {what:<62} {name} (+ .png)");
    Ok(())
}

/// Half of the mesh, cut facing the default (iso) view: the eye is on the +x, −y side.
fn half(axis: usize) -> Vec<Clip> {
    vec![Clip { axis, below: axis == 0, value: 0.5, relative: true }]
}

pub fn run(a: Args) -> Result<ExitCode> {
    let dir = &a.output;
    std::fs::create_dir_all(dir)?;
    let t = Instant::now();
    println!("qmesh demo: the 2022 query-replace applications on built-in inputs, into {}", dir.display());
    let by_type = RenderOptions::default();
    let view = RenderOptions { clip: half(1), ..by_type.clone() };

    // 1. A torus surface and its octree (Algorithm 5), then conformal transitions (Algorithm 7).
    let torus = torus_surface(1.0, 0.4, 48, 24);
    save(dir, "torus.off", &torus, &format!("torus surface: {} triangles", torus.nb_polygons()), by_type.clone())?;
    let bvh = TriangleBvh::from_polygons(&torus.points, (0..torus.nb_polygons()).map(|i| torus.polygon(i)));
    let opts = SubdivideOptions { levels: 5, remove_outside: true, ..Default::default() };
    let octree = subdivide(&bvh, &opts, None, &|_| {})?;
    let r = &octree.report;
    let what = format!("octree l_max 5: {} hexahedra, {} fqr, {} vqr", r.volumes, r.faces_replaced, r.volumes_replaced);
    save(dir, "torus_octree.vtk", &octree.mesh, &what, RenderOptions { color_by: ColorBy::Level, ..view.clone() })?;
    let transitions = generated_pattern_set(GeneratedKind::Transitions, FlagRule::Corners)?;
    let (map, c) = conformal(&octree.mesh, &transitions, true)?;
    let k = c.kinds;
    let what =
        format!("conformal: {} hex, {} pyramid, {} tet, valid {}", k.hex, k.pyramid, k.tet, map.is_valid().is_empty());
    save(dir, "torus_conformal.vtk", &extract(&map).0, &what, view)?;

    // 2. Marching cubes (Algorithm 6) of the torus's octree and of a field.
    let mc = mc_pattern_set();
    let (surface, r, _) =
        marching_cubes_surface(&bvh, 5, RootShape::Cube, 0.01, &mc, McFlags::Inside).map_err(anyhow::Error::msg)?;
    let tri = triangulate(&surface);
    let chi = build_surface_map(&tri)
        .map(|(m, _)| m.count_cells().euler_characteristic(2).to_string())
        .unwrap_or_else(|e| format!("unknown ({e})"));
    let what =
        format!("marching cubes of the octree: {} triangles, χ {chi}, {} cubes", tri.nb_polygons(), r.volumes_replaced);
    save(dir, "torus_marching_cubes.off", &tri, &what, by_type.clone())?;
    let n = 40usize;
    let field: Vec<f32> = (0..n * n * n)
        .map(|idx| {
            let (i, j, k) = (idx / (n * n), idx / n % n, idx % n);
            let p = [i, j, k].map(|x| x as f64 / (n - 1) as f64 * 4.0 * std::f64::consts::PI);
            (p[0].sin() * p[1].cos() + p[1].sin() * p[2].cos() + p[2].sin() * p[0].cos()) as f32
        })
        .collect();
    let (g, r) = marching_cubes_field(&field, [n, n, n], 0.0, &mc, McFlags::Inside).map_err(anyhow::Error::msg)?;
    let what = format!(
        "marching cubes of a gyroid field 40³: {} polygons, {} f-/{} v-patterns",
        g.nb_polygons(),
        r.f_patterns,
        r.v_patterns
    );
    save(dir, "gyroid.off", &g, &what, by_type.clone())?;

    // 3. Hexahedra split in 8 and tetrahedra into 4 hexahedra (query-replace, §7.1, §7.4).
    let (mut hex, _) = build_volume_map(&hex_grid(6, 4, 3), &BuildOptions::default())?;
    let subdivision = generated_pattern_set(GeneratedKind::HexSubdivision, FlagRule::Corners)?;
    let opts = ReplaceOptions { split_edges: Some(2), ..ReplaceOptions::default() };
    let r = query_replace(&mut hex, &subdivision, &opts)?;
    let what = format!("6×4×3 hex grid, each hex in 8: {} volumes replaced", r.volumes_replaced);
    save(
        dir,
        "hex_grid_subdivided.vtk",
        &extract(&hex).0,
        &what,
        RenderOptions { clip: half(0), color_by: ColorBy::Quality, ..by_type.clone() },
    )?;
    let (mut tet, _) = build_volume_map(&tet_grid(4, 4, 4), &BuildOptions::default())?;
    let r = tet_to_hex(&mut tet, None, true)?;
    let what = format!("384 tets into hexahedra: {} replaced, valid {}", r.volumes_replaced, tet.is_valid().is_empty());
    save(dir, "tet_grid_to_hex.vtk", &extract(&tet).0, &what, RenderOptions { clip: half(0), ..by_type.clone() })?;
    println!(
        "done in {:.2} s — open the .vtk files in ParaView, or try: qmesh info {}",
        t.elapsed().as_secs_f64(),
        dir.join("torus_conformal.vtk").display()
    );
    Ok(ExitCode::SUCCESS)
}
