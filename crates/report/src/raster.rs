//! A small software rasteriser for the animation: an indexed-colour image with a depth
//! buffer, shaded spheres (Lambert, one directional light) and flat lines and boxes.

/// Shading steps per hue in the palette.
pub const SHADES: u8 = 16;

/// Direction towards the light in view space (x right, y up, z towards the viewer), unit.
const LIGHT: [f32; 3] = [-0.40, 0.50, 0.768];

/// An image of palette indices with a depth per pixel (larger is nearer the viewer).
#[derive(Clone, Debug)]
pub struct Raster {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// Palette index per pixel, row-major from the top-left corner.
    pub pixels: Vec<u8>,
    depth: Vec<f32>,
}

/// A sphere in view space: pixel position (x right, y down), depth towards the viewer and
/// radius in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// Pixel column of the centre.
    pub x: f32,
    /// Pixel row of the centre.
    pub y: f32,
    /// Depth of the centre towards the viewer (pixels).
    pub depth: f32,
    /// Radius (pixels).
    pub radius: f32,
}

impl Raster {
    /// A `width` × `height` image filled with palette index `background`, depth −∞.
    pub fn new(width: usize, height: usize, background: u8) -> Self {
        Self {
            width,
            height,
            pixels: vec![background; width * height],
            depth: vec![f32::NEG_INFINITY; width * height],
        }
    }

    /// Draws `sphere` where it is nearer than what is there. The pixel gets palette index
    /// `first + shade` with shade ∈ 0..SHADES from the Lambert term (ambient 0.25).
    pub fn sphere(&mut self, sphere: Sphere, first: u8) {
        let r = sphere.radius.max(0.5);
        // No point of the sphere is nearer than its front, centre depth + r (dz ≤ 1, and
        // rounding is monotonic): a pixel already nearer than that keeps its colour.
        let front = sphere.depth + r;
        let x0 = ((sphere.x - r).floor().max(0.0)) as usize;
        let y0 = ((sphere.y - r).floor().max(0.0)) as usize;
        let x1 = ((sphere.x + r).ceil().max(0.0) as usize).min(self.width);
        let y1 = ((sphere.y + r).ceil().max(0.0) as usize).min(self.height);
        for py in y0..y1 {
            for px in x0..x1 {
                let i = py * self.width + px;
                if front <= self.depth[i] {
                    continue;
                }
                let dx = (px as f32 + 0.5 - sphere.x) / r;
                let dy = (sphere.y - py as f32 - 0.5) / r;
                let d2 = dx * dx + dy * dy;
                if d2 > 1.0 {
                    continue;
                }
                let dz = (1.0 - d2).sqrt();
                let z = sphere.depth + dz * r;
                if z <= self.depth[i] {
                    continue;
                }
                self.depth[i] = z;
                let lambert = (dx * LIGHT[0] + dy * LIGHT[1] + dz * LIGHT[2]).max(0.0);
                let shade = ((0.25 + 0.75 * lambert) * f32::from(SHADES - 1)).round() as u8;
                self.pixels[i] = first + shade.min(SHADES - 1);
            }
        }
    }

    /// Fills the pixels of columns `x0..x1`, rows `y0..y1` (clipped) with `index`, behind
    /// anything already drawn with a depth.
    pub fn fill(&mut self, (x0, x1): (usize, usize), (y0, y1): (usize, usize), index: u8) {
        for y in y0..y1.min(self.height) {
            for x in x0..x1.min(self.width) {
                if self.depth[y * self.width + x] == f32::NEG_INFINITY {
                    self.pixels[y * self.width + x] = index;
                }
            }
        }
    }

    /// Draws the line from pixel position `from` to `to` (column, row; clipped) with `index`,
    /// behind anything already drawn with a depth.
    pub fn line(&mut self, from: (f32, f32), to: (f32, f32), index: u8) {
        let steps = (to.0 - from.0).abs().max((to.1 - from.1).abs()).ceil().max(1.0) as usize;
        for k in 0..=steps {
            let w = k as f32 / steps as f32;
            let (x, y) = (from.0 + w * (to.0 - from.0), from.1 + w * (to.1 - from.1));
            if x >= 0.0 && y >= 0.0 {
                self.fill((x as usize, x as usize + 1), (y as usize, y as usize + 1), index);
            }
        }
    }

    /// Copies `other` into this image with its left edge at column `x` (clipped).
    pub fn paste(&mut self, other: &Raster, x: usize) {
        for row in 0..other.height.min(self.height) {
            let width = other.width.min(self.width.saturating_sub(x));
            let to = row * self.width + x;
            self.pixels[to..to + width]
                .copy_from_slice(&other.pixels[row * other.width..row * other.width + width]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_nearer_sphere_hides_a_farther_one_and_is_lit_on_the_light_side() {
        let mut r = Raster::new(40, 40, 0);
        r.sphere(Sphere { x: 20.0, y: 20.0, depth: 0.0, radius: 10.0 }, 100);
        r.sphere(Sphere { x: 20.0, y: 20.0, depth: -50.0, radius: 15.0 }, 200);
        let at = |x: usize, y: usize| r.pixels[y * 40 + x];
        assert!((100..100 + SHADES).contains(&at(20, 20)), "the nearer sphere covers the centre");
        assert!((200..200 + SHADES).contains(&at(20, 7)), "the bigger one shows around it");
        assert_eq!(at(0, 0), 0, "background outside both");
        // The light comes from the upper left: that side is brighter.
        assert!(at(16, 16) > at(24, 24), "{} vs {}", at(16, 16), at(24, 24));
    }

    #[test]
    fn a_line_joins_its_ends_and_is_clipped() {
        let mut r = Raster::new(10, 10, 0);
        r.line((1.0, 1.0), (8.0, 8.0), 3);
        assert!((1..=8).all(|k| r.pixels[k * 10 + k] == 3), "the diagonal");
        assert_eq!(r.pixels[10 + 8], 0, "off the line");
        r.line((-5.0, 5.0), (20.0, 5.0), 4);
        assert!((0..10).all(|x| r.pixels[50 + x] == 4), "clipped to the image");
    }

    #[test]
    fn fill_stays_behind_spheres_and_paste_copies_rows() {
        let mut r = Raster::new(10, 10, 0);
        r.sphere(Sphere { x: 5.0, y: 5.0, depth: 0.0, radius: 2.0 }, 10);
        r.fill((0, 10), (5, 6), 1);
        assert_eq!(r.pixels[5 * 10], 1);
        assert!(r.pixels[5 * 10 + 5] >= 10);
        let mut wide = Raster::new(20, 10, 0);
        wide.paste(&r, 10);
        assert_eq!(wide.pixels[5 * 20 + 10], 1);
        assert_eq!(wide.pixels[5 * 20 + 15], r.pixels[5 * 10 + 5]);
        assert_eq!(wide.pixels[5 * 20], 0);
    }
}
