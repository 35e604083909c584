//! Pictures of meshes as the papers draw them: every cell shrunk toward its centroid so
//! cells are seen apart, optionally cut open by a plane, flat-shaded, coloured by cell
//! type, level, quality, label or component, with edges and a legend.

use std::time::Instant;

use super::font::{draw_text, text_width};
use super::raster::{Canvas, Rgb};
use crate::build::{CellKind, CellValues, IndexedMesh, cell_scaled_jacobian};
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, cross, dot, sub};

/// What decides a cell's colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorBy {
    Type,
    Level,
    Quality,
    Label,
    Component,
}

/// Keep the cells whose centroid has coordinate `axis` below (or above) `value`, or,
/// when `relative`, below the fraction `value` of the mesh's extent along that axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Clip {
    pub axis: usize,
    pub below: bool,
    pub value: f64,
    pub relative: bool,
}

/// Options of [`render`].
#[derive(Clone, Debug)]
pub struct RenderOptions {
    /// Cells shrunk toward their centroid by this factor (1 = no gap).
    pub shrink: f64,
    /// Cells kept: those whose centroid passes every clip (all when empty).
    pub clip: Vec<Clip>,
    pub color_by: ColorBy,
    /// Viewing direction: azimuth and elevation in degrees (the eye's direction from
    /// the mesh centre; z is up).
    pub view: (f64, f64),
    pub size: (usize, usize),
    pub edges: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            shrink: 0.85,
            clip: Vec::new(),
            color_by: ColorBy::Type,
            view: (-55.0, 25.0),
            size: (1200, 900),
            edges: true,
        }
    }
}

/// What [`render`] drew.
#[derive(Clone, Debug, Default)]
pub struct RenderReport {
    pub cells: usize,
    pub cells_drawn: usize,
    pub triangles: usize,
    /// The legend's entries, top to bottom.
    pub legend: Vec<String>,
    pub seconds: f64,
}

/// Faces narrower than this on screen get no edge lines.
const MIN_EDGE_FACE_PIXELS: f64 = 5.0;

const PALETTE: [Rgb; 10] = [
    [78, 121, 167],
    [242, 142, 43],
    [225, 87, 89],
    [118, 183, 178],
    [89, 161, 79],
    [237, 201, 72],
    [176, 122, 161],
    [255, 157, 167],
    [156, 117, 95],
    [186, 176, 172],
];

fn type_colour(k: CellKind) -> Rgb {
    match k {
        CellKind::Hex => PALETTE[0],
        CellKind::Tet => PALETTE[2],
        CellKind::Prism => PALETTE[4],
        CellKind::Pyramid => PALETTE[1],
        CellKind::Polyhedron => PALETTE[6],
    }
}

/// Red (≤ 0) → yellow (0.5) → green (1) for a scaled Jacobian.
fn quality_colour(q: f64) -> Rgb {
    let t = q.clamp(0.0, 1.0);
    if t < 0.5 { [220, (60.0 + 340.0 * t) as u8, 50] } else { [(220.0 - 340.0 * (t - 0.5)) as u8, 200, 50] }
}

/// Camera: orthonormal right, up and forward (into the scene) vectors.
fn camera(view: (f64, f64)) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let (az, el) = (view.0.to_radians(), view.1.to_radians());
    let eye = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
    let f = eye.map(|c| -c);
    let up0 = if el.cos().abs() < 1e-6 { [0.0, 1.0, 0.0] } else { [0.0, 0.0, 1.0] };
    let r = normalise(cross(f, up0));
    (r, cross(r, f), f)
}

fn normalise(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    if n > 0.0 { a.map(|c| c / n) } else { a }
}

/// Per-cell colour and the legend entries.
fn colours(mesh: &IndexedMesh, by: ColorBy) -> (Vec<Rgb>, Vec<(Rgb, String)>) {
    let n = mesh.nb_cells();
    let categorical = |values: Vec<i64>, name: &str| {
        let mut distinct = values.clone();
        distinct.sort_unstable();
        distinct.dedup();
        let colour_of = |v: i64| PALETTE[distinct.binary_search(&v).unwrap_or(0) % PALETTE.len()];
        let legend = distinct.iter().take(10).map(|&v| (colour_of(v), format!("{name} {v}"))).collect();
        (values.iter().map(|&v| colour_of(v)).collect(), legend)
    };
    match by {
        ColorBy::Type => {
            let mut counts = [0usize; 5];
            let kinds = [CellKind::Tet, CellKind::Pyramid, CellKind::Prism, CellKind::Hex, CellKind::Polyhedron];
            mesh.kinds.iter().for_each(|k| counts[kinds.iter().position(|x| x == k).unwrap_or(4)] += 1);
            let legend = kinds
                .iter()
                .zip(counts)
                .filter(|(_, c)| *c > 0)
                .map(|(&k, c)| (type_colour(k), format!("{} {c}", k.name())))
                .collect();
            (mesh.kinds.iter().map(|&k| type_colour(k)).collect(), legend)
        }
        ColorBy::Level => match mesh.cell_array("level") {
            Some(CellValues::Int(v)) => categorical(v.iter().map(|&x| i64::from(x)).collect(), "level"),
            _ => categorical(vec![0; n], "level"),
        },
        ColorBy::Label => categorical((0..n).map(|i| i64::from(mesh.label(i).unwrap_or(0))).collect(), "label"),
        ColorBy::Component => categorical(components(mesh).into_iter().map(|c| c as i64).collect(), "component"),
        ColorBy::Quality => {
            let values: Vec<Option<f64>> = (0..n).map(|i| cell_scaled_jacobian(mesh, i)).collect();
            let q: Vec<Rgb> = values.iter().map(|v| v.map_or(PALETTE[9], quality_colour)).collect();
            (q, quality_legend(values.iter().flatten().copied()))
        }
    }
}

/// Legend entries spanning the scaled Jacobians present (the colours stay absolute:
/// red ≤ 0, yellow 0.5, green 1); one entry when they are all (nearly) equal.
fn quality_legend(values: impl Iterator<Item = f64>) -> Vec<(Rgb, String)> {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if lo > hi {
        return Vec::new();
    }
    if hi - lo < 5e-3 {
        return vec![(quality_colour(lo), format!("scaled jacobian: all {:.2}", 0.5 * (lo + hi)))];
    }
    (0..5)
        .map(|k| lo + (hi - lo) * f64::from(k) / 4.0)
        .rev()
        .map(|v| (quality_colour(v), format!("scaled jacobian {v:.2}")))
        .collect()
}

/// Connected components of cells sharing a vertex.
fn components(mesh: &IndexedMesh) -> Vec<usize> {
    let mut sets = DisjointSets::new(mesh.points.len());
    let nodes = |i: usize| mesh.cell_faces(i).unwrap_or_default().into_iter().flatten().collect::<Vec<u32>>();
    for i in 0..mesh.nb_cells() {
        let v = nodes(i);
        for w in v.windows(2) {
            sets.union(w[0], w[1]);
        }
    }
    let mut ids: Vec<usize> =
        (0..mesh.nb_cells()).map(|i| nodes(i).first().map_or(0, |&v| sets.find(v) as usize)).collect();
    let mut distinct = ids.clone();
    distinct.sort_unstable();
    distinct.dedup();
    ids.iter_mut().for_each(|c| *c = distinct.binary_search(c).unwrap_or(0));
    ids
}

/// Renders the cells of `mesh` (or its polygons, for a surface).
pub fn render(mesh: &IndexedMesh, opts: &RenderOptions) -> (Canvas, RenderReport) {
    render_titled(mesh, opts, None)
}

/// Height of the title band, in pixels.
const TITLE_BAND: usize = 34;

/// As [`render`], with a title line across the top (file, cells, colouring): the mesh
/// is fitted to the frame below it.
pub fn render_titled(mesh: &IndexedMesh, opts: &RenderOptions, title: Option<&str>) -> (Canvas, RenderReport) {
    let t = Instant::now();
    let (w, h) = opts.size;
    let mut canvas = Canvas::new(w, h);
    let mut report = RenderReport { cells: mesh.nb_cells().max(mesh.nb_polygons()), ..Default::default() };
    let (right, up, fwd) = camera(opts.view);
    let light = normalise([0, 1, 2].map(|k| -fwd[k] + 0.6 * up[k] - 0.4 * right[k]));
    // Cells kept (by the clip) with their faces (outward) and colours.
    let volume = mesh.is_volume();
    let (cell_colours, legend) = if volume { colours(mesh, opts.color_by) } else { (Vec::new(), Vec::new()) };
    report.legend = legend.iter().map(|l| l.1.clone()).collect();
    let faces_of = |i: usize| -> Vec<Vec<u32>> {
        if volume {
            mesh.cell_faces(i)
                .unwrap_or_default()
                .into_iter()
                .map(|mut f| {
                    f.reverse();
                    f
                })
                .collect()
        } else {
            vec![mesh.polygon(i).to_vec()]
        }
    };
    let count = if volume { mesh.nb_cells() } else { mesh.nb_polygons() };
    let centre_of = |faces: &[Vec<u32>]| {
        let pts: Vec<[f64; 3]> = faces.iter().flatten().map(|&v| mesh.points[v as usize]).collect();
        crate::geom::centroid(pts)
    };
    let whole = Aabb::of(mesh.points.iter().copied());
    let kept: Vec<bool> = (0..count)
        .map(|i| {
            if !volume || opts.clip.is_empty() {
                return true;
            }
            let centre = centre_of(&faces_of(i));
            opts.clip.iter().all(|c| {
                let v = if c.relative { whole.lo[c.axis] + c.value * whole.extent()[c.axis] } else { c.value };
                if c.below { centre[c.axis] < v } else { centre[c.axis] > v }
            })
        })
        .collect();
    let bounds = Aabb::of(
        (0..count)
            .filter(|&i| kept[i])
            .flat_map(|i| faces_of(i).into_iter().flatten())
            .map(|v| mesh.points[v as usize]),
    );
    let top = if title.is_some() { TITLE_BAND } else { 0 };
    if bounds.lo[0] > bounds.hi[0] {
        draw_legend(&mut canvas, &legend, top);
        draw_title(&mut canvas, title);
        report.seconds = t.elapsed().as_secs_f64();
        return (canvas, report);
    }
    let c = bounds.centre();
    let e = bounds.extent();
    let radius = (0.5 * dot(e, e).sqrt()).max(f64::MIN_POSITIVE);
    // Fit the kept points' extent on screen (not their bounding sphere) to 92 % of the
    // frame below the title.
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for i in (0..count).filter(|&i| kept[i]) {
        for v in faces_of(i).into_iter().flatten() {
            let d = sub(mesh.points[v as usize], c);
            let (x, y) = (dot(d, right), dot(d, up));
            (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
        }
    }
    let frame = Frame { width: w as f64, height: (h - top.min(h)) as f64, legend: legend_size(&legend) };
    let fit = frame.fit(x1 - x0, y1 - y0);
    let (mx, my) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let project = |p: [f64; 3]| {
        let d = sub(p, c);
        let (x, y) = (dot(d, right) - mx, dot(d, up) - my);
        [fit.centre[0] + fit.scale * x, top as f64 + fit.centre[1] - fit.scale * y, dot(d, fwd)]
    };
    let bias = 1e-3 * radius;
    for i in (0..count).filter(|&i| kept[i]) {
        let faces = faces_of(i);
        let cc = centre_of(&faces);
        let shrink = if volume { opts.shrink } else { 1.0 };
        let place = |v: u32| {
            let p = mesh.points[v as usize];
            [0, 1, 2].map(|k| cc[k] + shrink * (p[k] - cc[k]))
        };
        let base = if volume { cell_colours[i] } else { [150, 180, 220] };
        report.cells_drawn += 1;
        for f in &faces {
            let pts: Vec<[f64; 3]> = f.iter().map(|&v| place(v)).collect();
            let mut n = [0.0; 3];
            for k in 0..pts.len() {
                let c = cross(pts[k], pts[(k + 1) % pts.len()]);
                n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]];
            }
            let mut n = normalise(n);
            if dot(n, fwd) > 0.0 {
                if volume {
                    continue; // back face
                }
                n = n.map(|x| -x); // surfaces are two-sided
            }
            let shade = 0.35 + 0.65 * dot(n, light).max(0.0);
            let colour = base.map(|x| (f64::from(x) * shade).min(255.0) as u8);
            let sp: Vec<[f64; 3]> = pts.iter().map(|&p| project(p)).collect();
            for k in 1..sp.len().saturating_sub(1) {
                canvas.triangle([sp[0], sp[k], sp[k + 1]], colour);
                report.triangles += 1;
            }
            // Edges of faces a few pixels wide would only darken the picture.
            let span = sp.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| (lo.min(p[0]), hi.max(p[0])));
            if opts.edges && span.1 - span.0 > MIN_EDGE_FACE_PIXELS {
                for k in 0..sp.len() {
                    canvas.line(sp[k], sp[(k + 1) % sp.len()], [40, 40, 40], bias);
                }
            }
        }
    }
    draw_legend(&mut canvas, &legend, top);
    draw_title(&mut canvas, title);
    report.seconds = t.elapsed().as_secs_f64();
    (canvas, report)
}

/// The title line, on a white band across the top.
fn draw_title(canvas: &mut Canvas, title: Option<&str>) {
    let Some(title) = title else { return };
    let w = canvas.width;
    canvas.rect(0, 0, w, TITLE_BAND - 4, [255, 255, 255]);
    // Half size when the title would run off the picture at full size.
    let scale = if 12 + text_width(title, 2) <= w { 2 } else { 1 };
    draw_text(canvas, 12, 6 + 4 * (2 - scale), title, scale, [20, 20, 20]);
}

/// Text scale, row height and left edge of the legend's entries, and its margin.
const LEGEND_SCALE: usize = 2;
const LEGEND_ROW: usize = 22;
const LEGEND_TEXT_X: usize = 34;
const LEGEND_MARGIN: usize = 12;

/// Width and height of the legend's box in the top left corner (0 × 0 without one).
fn legend_size(legend: &[(Rgb, String)]) -> (f64, f64) {
    let widest = legend.iter().map(|(_, t)| text_width(t, LEGEND_SCALE)).max();
    widest.map_or((0.0, 0.0), |t| {
        ((LEGEND_TEXT_X + t + LEGEND_MARGIN) as f64, (LEGEND_MARGIN + legend.len() * LEGEND_ROW) as f64)
    })
}

/// The drawing area below the title, with the legend's box in its top left corner.
struct Frame {
    width: f64,
    height: f64,
    legend: (f64, f64),
}

/// Where the mesh goes: pixels per unit and the screen point of its extent's centre.
#[derive(Debug, PartialEq)]
struct Fit {
    scale: f64,
    centre: [f64; 2],
}

impl Frame {
    /// The largest fit of an extent `dx` × `dy` (to 92 % of the space) that keeps clear
    /// of the legend: the whole frame when that misses the legend's box, else beside
    /// it or below it, whichever draws the mesh larger.
    fn fit(&self, dx: f64, dy: f64) -> Fit {
        let in_box = |x: f64, y: f64, w: f64, h: f64| {
            let scale = 0.92 * (w / dx.max(1e-12)).min(h / dy.max(1e-12));
            Fit { scale, centre: [x + w / 2.0, y + h / 2.0] }
        };
        let (lw, lh) = self.legend;
        let whole = in_box(0.0, 0.0, self.width, self.height);
        let (left, top) = (whole.centre[0] - whole.scale * dx / 2.0, whole.centre[1] - whole.scale * dy / 2.0);
        if lw == 0.0 || left >= lw || top >= lh {
            return whole;
        }
        let beside = in_box(lw, 0.0, (self.width - lw).max(1.0), self.height);
        let below = in_box(0.0, lh, self.width, (self.height - lh).max(1.0));
        if beside.scale >= below.scale { beside } else { below }
    }
}

fn draw_legend(canvas: &mut Canvas, legend: &[(Rgb, String)], top: usize) {
    let scale = LEGEND_SCALE;
    for (k, (colour, text)) in legend.iter().enumerate() {
        let y = top + LEGEND_MARGIN + k * LEGEND_ROW;
        canvas.rect(LEGEND_MARGIN, y, 16, 16, [40, 40, 40]);
        canvas.rect(LEGEND_MARGIN + 2, y + 2, 12, 12, *colour);
        canvas.rect(LEGEND_TEXT_X, y, text_width(text, scale), 16, [255, 255, 255]);
        draw_text(canvas, LEGEND_TEXT_X + 2, y + 1, text, scale, [20, 20, 20]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mesh's box on screen for an extent `dx` × `dy`: (left, top, right, bottom).
    fn screen_box(fit: &Fit, dx: f64, dy: f64) -> [f64; 4] {
        let (hw, hh) = (fit.scale * dx / 2.0, fit.scale * dy / 2.0);
        [fit.centre[0] - hw, fit.centre[1] - hh, fit.centre[0] + hw, fit.centre[1] + hh]
    }

    #[test]
    fn the_mesh_keeps_clear_of_the_legend() {
        let frame = |legend| Frame { width: 800.0, height: 600.0, legend };
        // Without a legend: 92 % of the frame, centred.
        assert_eq!(frame((0.0, 0.0)).fit(4.0, 3.0), Fit { scale: 0.92 * 200.0, centre: [400.0, 300.0] });
        // A wide mesh would run under a legend 290 × 122 in the corner: it goes below
        // (a tall one beside), never into the legend's box, as large as it can.
        for (dx, dy) in [(4.0, 2.0), (1.0, 3.0), (4.0, 3.0)] {
            let fit = frame((290.0, 122.0)).fit(dx, dy);
            let [l, t, r, b] = screen_box(&fit, dx, dy);
            assert!(l >= 290.0 || t >= 122.0, "{dx} × {dy}: {:?} overlaps the legend", [l, t, r, b]);
            assert!(l >= 0.0 && t >= 0.0 && r <= 800.0 && b <= 600.0, "{dx} × {dy} leaves the frame");
            let plain = |width, height| Frame { width, height, legend: (0.0, 0.0) }.fit(dx, dy).scale;
            assert_eq!(fit.scale, plain(800.0 - 290.0, 600.0).max(plain(800.0, 600.0 - 122.0)), "{dx} × {dy}");
        }
        // A mesh that misses the legend anyway keeps the whole frame.
        let narrow = frame((100.0, 50.0)).fit(1.0, 1.0);
        assert_eq!(narrow, frame((0.0, 0.0)).fit(1.0, 1.0));
    }
}
