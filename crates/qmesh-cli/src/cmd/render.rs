//! `qmesh render IN -o OUT.png`: a picture of the mesh, cells shrunk apart, optionally
//! cut open, coloured by type, level, quality, label or component.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Result, bail};
use qmesh::io::{IoError, Loaded, read, write_atomically};
use qmesh::render::{Clip, ColorBy, RenderOptions, render_titled};
use serde_json::json;

use super::parse_format;

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum ColorArg {
    Type,
    Level,
    Quality,
    Label,
    Component,
}

#[derive(clap::Args, Debug)]
pub struct Args {
    /// Mesh or surface to draw.
    pub input: PathBuf,
    /// Output PNG.
    #[arg(short, long)]
    pub output: PathBuf,
    /// Allow the output to be the input file (a mesh read with `--format` from a file
    /// named .png).
    #[arg(long)]
    pub force: bool,
    /// Cells shrunk toward their centroid by this factor (1 = no gap).
    #[arg(long, default_value_t = 0.85)]
    pub shrink: f64,
    /// Keep the cells whose centroid satisfies AXIS < VALUE or AXIS > VALUE (e.g. x<0.5, or
    /// x<50% of the mesh's extent); repeat to keep a box (--clip x>2 --clip x<3).
    #[arg(long)]
    pub clip: Vec<String>,
    /// Cell colours.
    #[arg(long, value_enum, default_value = "type")]
    pub color_by: ColorArg,
    /// iso, x, y, z (looking from that axis), or AZ,EL in degrees (may be negative).
    #[arg(long, default_value = "iso", allow_hyphen_values = true)]
    pub view: String,
    /// Image size W,H in pixels.
    #[arg(long, default_value = "1200,900")]
    pub size: String,
    /// Do not draw cell edges.
    #[arg(long)]
    pub no_edges: bool,
    /// Input format, overriding the extension.
    #[arg(long)]
    pub format: Option<String>,
    #[command(flatten)]
    pub report: super::ReportArgs,
}

fn parse_clip(s: &str) -> Result<Clip> {
    let (axis_part, below, value) = if let Some((a, v)) = s.split_once('<') {
        (a, true, v)
    } else if let Some((a, v)) = s.split_once('>') {
        (a, false, v)
    } else {
        bail!("--clip {s}: expected AXIS<VALUE or AXIS>VALUE, e.g. x<0.5 or x<50%");
    };
    let axis = match axis_part.trim() {
        "x" => 0,
        "y" => 1,
        "z" => 2,
        other => bail!("--clip {s}: axis '{other}' is not x, y or z"),
    };
    let (number, relative) = match value.trim().strip_suffix('%') {
        Some(v) => (v, true),
        None => (value.trim(), false),
    };
    let value: f64 = number.parse().map_err(|_| anyhow::anyhow!("--clip {s}: '{value}' is not a number"))?;
    Ok(Clip { axis, below, value: if relative { value / 100.0 } else { value }, relative })
}

fn parse_view(s: &str) -> Result<(f64, f64)> {
    Ok(match s {
        "iso" => RenderOptions::default().view,
        "x" => (0.0, 0.0),
        "y" => (90.0, 0.0),
        "z" => (-90.0, 90.0),
        _ => {
            let v: Vec<f64> = s
                .split(',')
                .map(|x| x.trim().parse())
                .collect::<Result<_, _>>()
                .map_err(|_| anyhow::anyhow!("--view {s}: expected iso, x, y, z or AZ,EL in degrees"))?;
            match v[..] {
                [az, el] if el.abs() <= 90.0 => (az, el),
                _ => bail!("--view {s}: expected AZ,EL with EL in [-90, 90]"),
            }
        }
    })
}

fn parse_size(s: &str) -> Result<(usize, usize)> {
    let v: Vec<usize> = s
        .split(',')
        .map(|x| x.trim().parse())
        .collect::<Result<_, _>>()
        .map_err(|_| anyhow::anyhow!("--size {s}: expected W,H"))?;
    match v[..] {
        [w, h] if (16..=16384).contains(&w) && (16..=16384).contains(&h) => Ok((w, h)),
        _ => bail!("--size {s}: expected W,H between 16 and 16384"),
    }
}

pub fn run(a: Args) -> Result<ExitCode> {
    if a.output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() != Some("png") {
        bail!("{}: the output of render is a .png file", a.output.display());
    }
    super::refuse_to_overwrite(&a.input, &a.output, a.force)?;
    if !(0.0..=1.0).contains(&a.shrink) {
        bail!("--shrink {} is outside [0, 1]", a.shrink);
    }
    let opts = RenderOptions {
        shrink: a.shrink,
        clip: a.clip.iter().map(|c| parse_clip(c)).collect::<Result<_>>()?,
        color_by: match a.color_by {
            ColorArg::Type => ColorBy::Type,
            ColorArg::Level => ColorBy::Level,
            ColorArg::Quality => ColorBy::Quality,
            ColorArg::Label => ColorBy::Label,
            ColorArg::Component => ColorBy::Component,
        },
        view: parse_view(&a.view)?,
        size: parse_size(&a.size)?,
        edges: !a.no_edges,
    };
    let mesh = match read(&a.input, parse_format(&a.format)?)? {
        Loaded::Indexed(m) => m,
        Loaded::Map(map) => qmesh::build::extract(&map).0,
    };
    let pb = crate::progress::spinner("render", a.report.quiet || a.report.json);
    let colouring = match opts.color_by {
        ColorBy::Type => "cell type",
        ColorBy::Level => "level",
        ColorBy::Quality => "scaled Jacobian",
        ColorBy::Label => "label",
        ColorBy::Component => "component",
    };
    let cells = if mesh.is_volume() { mesh.nb_cells() } else { mesh.nb_polygons() };
    let name = a.input.file_name().map_or_else(|| a.input.display().to_string(), |n| n.to_string_lossy().into_owned());
    let clipped = if a.clip.is_empty() { String::new() } else { format!(", clipped {}", a.clip.join(" ")) };
    let title = format!(
        "{name} - {cells} {} - coloured by {colouring}{clipped}",
        if mesh.is_volume() { "cells" } else { "polygons" }
    );
    let (canvas, r) = render_titled(&mesh, &opts, Some(&title));
    pb.finish_and_clear();
    write_atomically(&a.output, |w| canvas.write_png(w).map_err(|e| IoError::io(&a.output, e)))?;
    if a.report.json {
        let j = json!({
            "input": a.input.display().to_string(), "output": a.output.display().to_string(),
            "cells": r.cells, "cells_drawn": r.cells_drawn, "triangles": r.triangles,
            "title": title, "legend": r.legend,
            "render_seconds": r.seconds, "peak_memory_bytes": crate::memory::peak_rss_bytes(),
        });
        println!("{}", serde_json::to_string_pretty(&j)?);
    } else if !a.report.quiet {
        println!(
            "{} of {} cells drawn ({} triangles) in {:.3} s; wrote {}",
            r.cells_drawn,
            r.cells,
            r.triangles,
            r.seconds,
            a.output.display()
        );
    }
    Ok(ExitCode::SUCCESS)
}
