//! A z-buffered software rasteriser: flat-coloured triangles, depth-tested lines and
//! an RGB canvas written as PNG. No GPU, no display.

use std::io::Write;

/// RGB colour.
pub type Rgb = [u8; 3];

/// An image with a depth buffer (smaller depth = nearer the viewer).
#[derive(Clone, Debug)]
pub struct Canvas {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<Rgb>,
    depth: Vec<f32>,
}

impl Canvas {
    /// A white canvas.
    pub fn new(width: usize, height: usize) -> Canvas {
        Canvas { width, height, pixels: vec![[255; 3]; width * height], depth: vec![f32::INFINITY; width * height] }
    }

    /// Fills triangle `t` (pixel x, pixel y, depth) with `colour` where it is nearest.
    pub fn triangle(&mut self, t: [[f64; 3]; 3], colour: Rgb) {
        let [a, b, c] = t;
        let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
        if area.abs() < 1e-12 {
            return;
        }
        let x0 = a[0].min(b[0]).min(c[0]).floor().max(0.0) as usize;
        let y0 = a[1].min(b[1]).min(c[1]).floor().max(0.0) as usize;
        let x1 = (a[0].max(b[0]).max(c[0]).ceil() as usize).min(self.width.saturating_sub(1));
        let y1 = (a[1].max(b[1]).max(c[1]).ceil() as usize).min(self.height.saturating_sub(1));
        if x0 > x1 || y0 > y1 {
            return;
        }
        let edge = |p: [f64; 3], q: [f64; 3], x: f64, y: f64| (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0]);
        for y in y0..=y1 {
            let py = y as f64 + 0.5;
            for x in x0..=x1 {
                let px = x as f64 + 0.5;
                let (w0, w1, w2) = (edge(b, c, px, py) / area, edge(c, a, px, py) / area, edge(a, b, px, py) / area);
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = (w0 * a[2] + w1 * b[2] + w2 * c[2]) as f32;
                let i = y * self.width + x;
                if z < self.depth[i] {
                    self.depth[i] = z;
                    self.pixels[i] = colour;
                }
            }
        }
    }

    /// Draws the segment p–q (pixel x, y, depth) where it is not behind a surface by
    /// more than `bias` (so edges of the faces they bound show).
    pub fn line(&mut self, p: [f64; 3], q: [f64; 3], colour: Rgb, bias: f64) {
        let steps = (q[0] - p[0]).abs().max((q[1] - p[1]).abs()).ceil().max(1.0) as usize;
        for s in 0..=steps {
            let t = s as f64 / steps as f64;
            let (x, y) = (p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]));
            if x < 0.0 || y < 0.0 {
                continue;
            }
            let (x, y) = (x as usize, y as usize);
            if x >= self.width || y >= self.height {
                continue;
            }
            let z = (p[2] + t * (q[2] - p[2]) - bias) as f32;
            let i = y * self.width + x;
            if z <= self.depth[i] {
                self.pixels[i] = colour;
            }
        }
    }

    /// Fills a rectangle (for legends), ignoring depth.
    pub fn rect(&mut self, x: usize, y: usize, w: usize, h: usize, colour: Rgb) {
        for yy in y..(y + h).min(self.height) {
            for xx in x..(x + w).min(self.width) {
                self.pixels[yy * self.width + xx] = colour;
            }
        }
    }

    /// Writes the canvas as an 8-bit RGB PNG.
    ///
    /// # Errors
    /// Write failures.
    pub fn write_png(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let mut enc = png::Encoder::new(w, self.width as u32, self.height as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(std::io::Error::other)?;
        let data: Vec<u8> = self.pixels.iter().flatten().copied().collect();
        writer.write_image_data(&data).map_err(std::io::Error::other)?;
        writer.finish().map_err(std::io::Error::other)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearer_triangle_wins() {
        let mut c = Canvas::new(20, 20);
        c.triangle([[0.0, 0.0, 5.0], [20.0, 0.0, 5.0], [0.0, 20.0, 5.0]], [255, 0, 0]);
        c.triangle([[0.0, 0.0, 1.0], [20.0, 0.0, 1.0], [0.0, 20.0, 1.0]], [0, 0, 255]);
        c.triangle([[0.0, 0.0, 9.0], [20.0, 0.0, 9.0], [0.0, 20.0, 9.0]], [0, 255, 0]);
        assert_eq!(c.pixels[2 * 20 + 2], [0, 0, 255]);
        assert_eq!(c.pixels[19 * 20 + 19], [255, 255, 255], "outside the triangles");
        let mut png = Vec::new();
        c.write_png(&mut png).unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }
}
