//! The animated GIF: the body as shaded tubes (spheres swept along the centreline, radius
//! per body, coloured by arc length) in a top view (x–y) and a side view (x–z) side by
//! side, with the wall x = 0, the obstacles' wireframes and a time bar. Frames are
//! subsampled to at most [`MAX_FRAMES`]; it plays at [`SPEED_UP`] × real time.

use std::borrow::Cow;
use std::path::Path;

use crate::colour::{Rgb, sequential};
use crate::error::ReportError;
use crate::obstacles::{self, ObstacleTrack};
use crate::raster::{Raster, SHADES, Sphere};
use crate::run_dir::RunDir;

/// Size of one view (pixels).
pub const VIEW: (usize, usize) = (320, 240);
/// Most frames in the GIF.
pub const MAX_FRAMES: usize = 100;
/// Playback speed relative to simulated time.
pub const SPEED_UP: f64 = 4.0;

/// Palette indices: background, wall and frame lines, time bar, then the hue × shade ramp.
const BACKGROUND: u8 = 0;
const LINE: u8 = 1;
const BAR: u8 = 2;
const FIRST_HUE: u8 = 3;
/// Hues along the body (head → tail).
const HUES: u8 = 14;
/// Spheres per pixel-radius along a segment.
const SPHERES_PER_RADIUS: f32 = 3.0;
/// Border around the body in a view (pixels).
const BORDER: f64 = 8.0;

/// A view: the world axes along the image's right and up, and the one towards the viewer.
#[derive(Clone, Copy, Debug)]
struct View {
    right: usize,
    up: usize,
    towards: usize,
    /// +1 if the viewer looks down `-towards` (sits on the + side), −1 otherwise.
    sign: f64,
}

/// Top view: x right, y up, seen from +z. Side view: x right, z up, seen from −y.
const VIEWS: [View; 2] = [
    View { right: 0, up: 1, towards: 2, sign: 1.0 },
    View { right: 0, up: 2, towards: 1, sign: -1.0 },
];

/// The GIF palette (RGB triplets).
fn palette() -> Vec<u8> {
    let mut colours: Vec<Rgb> = vec![[252, 252, 250], [170, 170, 170], [70, 70, 70]];
    for h in 0..HUES {
        let base = sequential(f64::from(h) / f64::from(HUES - 1));
        for s in 0..SHADES {
            let k = f64::from(s) / f64::from(SHADES - 1);
            colours.push(base.map(|c| (f64::from(c) * k).round() as u8));
        }
    }
    colours.concat()
}

/// Pixel mapping shared by all frames: one scale for both views, each centred on the run's
/// bounding box.
#[derive(Clone, Copy, Debug)]
struct Projection {
    scale: f64,
    centre: [f64; 3],
}

impl Projection {
    fn fit(run: &RunDir) -> Self {
        let (low, high) = run.centreline.bounds();
        let margin = run.radii.values.iter().fold(0.0, |m: f64, r| m.max(*r));
        let extent = |a: usize| (high[a] - low[a] + 2.0 * margin).max(1e-6);
        let (w, h) = (VIEW.0 as f64 - 2.0 * BORDER, VIEW.1 as f64 - 2.0 * BORDER);
        let scale = VIEWS
            .iter()
            .map(|v| (w / extent(v.right)).min(h / extent(v.up)))
            .fold(f64::INFINITY, f64::min);
        Self { scale, centre: [0, 1, 2].map(|a| 0.5 * (low[a] + high[a])) }
    }

    /// (column, row, depth) in pixels of world point `p` in `view`.
    fn project(&self, view: View, p: [f64; 3]) -> (f32, f32, f32) {
        let x = 0.5 * VIEW.0 as f64 + (p[view.right] - self.centre[view.right]) * self.scale;
        let y = 0.5 * VIEW.1 as f64 - (p[view.up] - self.centre[view.up]) * self.scale;
        let z = view.sign * (p[view.towards] - self.centre[view.towards]) * self.scale;
        (x as f32, y as f32, z as f32)
    }
}

/// Draws frame `f` of `run` in `view`, with the obstacles where `obstacles` has them.
fn draw_view(
    run: &RunDir,
    (projection, obstacles): (&Projection, &[ObstacleTrack]),
    view: View,
    f: usize,
) -> Raster {
    let mut image = Raster::new(VIEW.0, VIEW.1, BACKGROUND);
    // The wall x = 0 (both views have x to the right).
    let wall = 0.5 * VIEW.0 as f64 - projection.centre[0] * projection.scale;
    if wall >= 0.0 && wall < VIEW.0 as f64 {
        image.fill((wall as usize, wall as usize + 2), (0, VIEW.1), LINE);
    }
    for polyline in &obstacles::at_frame(obstacles, f) {
        for pair in polyline.windows(2) {
            let (a, b) = (projection.project(view, pair[0]), projection.project(view, pair[1]));
            image.line((a.0, a.1), (b.0, b.1), LINE);
        }
    }
    let points = run.centreline.frame(f);
    let radii = &run.radii.values;
    let last = points.len() - 1;
    for b in 0..last {
        let (a, c) = (projection.project(view, points[b]), projection.project(view, points[b + 1]));
        let (ra, rc) =
            ((radii[b] * projection.scale) as f32, (radii[b + 1] * projection.scale) as f32);
        let length = ((c.0 - a.0).powi(2) + (c.1 - a.1).powi(2) + (c.2 - a.2).powi(2)).sqrt();
        let steps = ((length * SPHERES_PER_RADIUS / ra.min(rc).max(0.5)).ceil() as usize).max(1);
        for k in 0..=steps {
            let w = k as f32 / steps as f32;
            let hue = ((b as f32 + w) / last as f32 * f32::from(HUES - 1)).round() as u8;
            let sphere = Sphere {
                x: a.0 + w * (c.0 - a.0),
                y: a.1 + w * (c.1 - a.1),
                depth: a.2 + w * (c.2 - a.2),
                radius: ra + w * (rc - ra),
            };
            image.sphere(sphere, FIRST_HUE + hue * SHADES);
        }
    }
    image
}

/// The frames shown: every `step`-th, so that at most [`MAX_FRAMES`] remain, and the last.
pub fn shown_frames(frames: usize) -> Vec<usize> {
    let step = frames.div_ceil(MAX_FRAMES).max(1);
    let mut shown: Vec<usize> = (0..frames).step_by(step).collect();
    if frames > 0 && shown.last() != Some(&(frames - 1)) {
        shown.push(frames - 1);
    }
    shown
}

/// Encodes the animation of `run` as GIF bytes; `at` names the file for errors.
pub fn encode(run: &RunDir, at: &Path) -> Result<Vec<u8>, ReportError> {
    let projection = Projection::fit(run);
    let tracks = obstacles::tracks(run);
    let times = &run.centreline.times;
    let (width, height) = (VIEW.0 * VIEWS.len() + VIEWS.len() - 1, VIEW.1);
    let mut bytes = Vec::new();
    let (w16, h16) = (width as u16, height as u16);
    let mut encoder =
        gif::Encoder::new(&mut bytes, w16, h16, &palette()).map_err(ReportError::draw(at))?;
    encoder.set_repeat(gif::Repeat::Infinite).map_err(ReportError::draw(at))?;
    let shown = shown_frames(run.centreline.frames());
    let (start, end) = (times[0], times[times.len() - 1]);
    for (i, &f) in shown.iter().enumerate() {
        let mut canvas = Raster::new(width, height, LINE);
        for (v, view) in VIEWS.iter().enumerate() {
            let drawn = draw_view(run, (&projection, &tracks), *view, f);
            canvas.paste(&drawn, v * (VIEW.0 + 1));
        }
        let progress = if end > start { (times[f] - start) / (end - start) } else { 1.0 };
        canvas.fill((0, (progress * width as f64) as usize), (height - 3, height), BAR);
        let next = shown.get(i + 1).map_or(times[f], |n| times[*n]);
        let delay = ((next - times[f]) * 100.0 / SPEED_UP).round().clamp(2.0, 500.0) as u16;
        let frame = gif::Frame {
            width: w16,
            height: h16,
            delay: if i + 1 == shown.len() { 150 } else { delay },
            buffer: Cow::Borrowed(&canvas.pixels),
            ..gif::Frame::default()
        };
        encoder.write_frame(&frame).map_err(ReportError::draw(at))?;
    }
    encoder.into_inner().map_err(ReportError::draw(at))?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_subsampled_to_at_most_the_limit_and_keep_the_last() {
        assert_eq!(shown_frames(3), vec![0, 1, 2]);
        let shown = shown_frames(301);
        assert!(shown.len() <= MAX_FRAMES + 1, "{}", shown.len());
        assert_eq!((shown[0], shown[1], shown[shown.len() - 1]), (0, 4, 300));
        assert!(shown_frames(0).is_empty());
    }

    #[test]
    fn the_palette_fits_a_gif() {
        let p = palette();
        assert_eq!(p.len() % 3, 0);
        assert!(p.len() / 3 <= 256);
        assert_eq!(p.len() / 3, usize::from(FIRST_HUE) + usize::from(HUES) * usize::from(SHADES));
    }
}
