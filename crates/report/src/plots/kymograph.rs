//! Kymograph: a quantity per joint and frame as a joint × time heatmap (one axis of the
//! thigmotaxic force field, the thesis' Figure 6.2 as a picture; the tension along the body),
//! diverging colours centred at zero with symmetric limits, and a colour bar.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::figure::{DrawResult, Figure};
use super::rgb;
use crate::colour::diverging;
use crate::font::FAMILY;

/// The quantile of the non-zero magnitudes that sets the colour limits.
pub const PERCENTILE: f64 = 0.99;

/// Colour steps on each side of zero.
const LEVELS: i32 = 16;

/// A joint × time field and how to label it.
#[derive(Clone, Copy, Debug)]
pub struct Kymograph<'a> {
    /// Simulation time of each frame (s).
    pub times: &'a [f64],
    /// Joints per frame (0 = head).
    pub joints: usize,
    /// The values, frames × joints, frame-major (`values[f * joints + j]`).
    pub values: &'a [f64],
    /// Caption above the heatmap.
    pub caption: &'a str,
    /// Unit shown on the colour bar.
    pub unit: &'a str,
}

impl Kymograph<'_> {
    /// The colour-bar limit: the [`PERCENTILE`] of the non-zero magnitudes on the axis (a
    /// few spikes would otherwise wash out the rest), or 1 if all are zero. Larger values
    /// take the end colours.
    pub fn limit(&self) -> f64 {
        let mut magnitudes: Vec<f64> =
            self.values.iter().map(|v| v.abs()).filter(|v| *v > 0.0).collect();
        if magnitudes.is_empty() {
            return 1.0;
        }
        magnitudes.sort_unstable_by(f64::total_cmp);
        magnitudes[((magnitudes.len() - 1) as f64 * PERCENTILE).floor() as usize]
    }

    /// Runs of equal colour along time, per joint: (first frame, last frame, joint, level).
    fn runs(&self) -> Vec<(usize, usize, usize, i32)> {
        let (frames, joints) = (self.times.len(), self.joints);
        let values = self.values;
        let limit = self.limit();
        let level = |value: f64| {
            let l = f64::from(LEVELS);
            ((value / limit) * l).round().clamp(-l, l) as i32
        };
        let mut runs = Vec::new();
        for j in 0..joints {
            let mut f = 0;
            while f < frames {
                let (start, colour) = (f, level(values[f * joints + j]));
                while f < frames && level(values[f * joints + j]) == colour {
                    f += 1;
                }
                runs.push((start, f - 1, j, colour));
            }
        }
        runs
    }

    fn draw_colour_bar<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let limit = self.limit();
        let mut bar = ChartBuilder::on(area)
            .margin_top(40)
            .margin_bottom(44)
            .margin_right(12)
            .y_label_area_size(76)
            .build_cartesian_2d(0.0..1.0, -limit..limit)?;
        bar.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_labels(5)
            .y_label_formatter(&|v| format!("{v:.1e}"))
            .label_style((FAMILY, 11))
            .draw()?;
        let step = limit / f64::from(LEVELS);
        bar.draw_series((-LEVELS..=LEVELS).map(|l| {
            let centre = f64::from(l) * step;
            let bottom = (centre - 0.5 * step).max(-limit);
            let top = (centre + 0.5 * step).min(limit);
            Rectangle::new(
                [(0.0, bottom), (1.0, top)],
                rgb(diverging(f64::from(l) / f64::from(LEVELS))).filled(),
            )
        }))?;
        let label = format!("{}, clipped", self.unit);
        area.draw_text(&label, &(FAMILY, 11).into_text_style(area), (30, 16))?;
        Ok(())
    }
}

impl Figure for Kymograph<'_> {
    fn size(&self) -> (u32, u32) {
        (820, 420)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let (main, bar) = root.split_horizontally(680);
        let edges = cell_edges(self.times);
        let joints = self.joints.max(1) as f64;
        let all_zero = if self.values.iter().any(|v| *v != 0.0) { "" } else { " (all zero)" };
        let mut chart = ChartBuilder::on(&main)
            .caption(format!("{}{all_zero}", self.caption), (FAMILY, 18))
            .margin(10)
            .x_label_area_size(40)
            .y_label_area_size(52)
            .build_cartesian_2d(edges[0]..edges[edges.len() - 1], 0.0..joints)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("time (s)")
            .y_desc("joint (0 = head)")
            .y_label_formatter(&|v| format!("{v:.0}"))
            .label_style((FAMILY, 12))
            .axis_desc_style((FAMILY, 14))
            .draw()?;
        chart.draw_series(self.runs().into_iter().map(|(first, last, j, level)| {
            let colour = rgb(diverging(f64::from(level) / f64::from(LEVELS)));
            Rectangle::new(
                [(edges[first], j as f64), (edges[last + 1], j as f64 + 1.0)],
                colour.filled(),
            )
        }))?;
        self.draw_colour_bar(&bar)
    }
}

/// Cell boundaries in time: midpoints between frames, half a spacing beyond the ends
/// (`[0, 1]` with no frame, ±0.05 s around a single one).
fn cell_edges(times: &[f64]) -> Vec<f64> {
    match times {
        [] => vec![0.0, 1.0],
        [t] => vec![t - 0.05, t + 0.05],
        [first, second, ..] => {
            let (before_last, last) = (times[times.len() - 2], times[times.len() - 1]);
            let mut edges = vec![first - 0.5 * (second - first)];
            edges.extend(times.windows(2).map(|w| 0.5 * (w[0] + w[1])));
            edges.push(last + 0.5 * (last - before_last));
            edges
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_surround_the_frames() {
        assert_eq!(cell_edges(&[]), vec![0.0, 1.0]);
        assert_eq!(cell_edges(&[0.0, 0.25, 0.75]), vec![-0.125, 0.125, 0.5, 1.0]);
        assert_eq!(cell_edges(&[2.0]), vec![1.95, 2.05]);
    }

    #[test]
    fn runs_merge_equal_colours_and_cover_every_cell_once() {
        let times = [0.0, 0.1, 0.2, 0.3];
        // frame-major: (f0 j0, f0 j1), (f1 j0, f1 j1), …
        let values = [0.0, 4.0, 0.0, 4.0, -4.0, 4.0, 0.0, 4.0];
        let k = Kymograph { times: &times, joints: 2, values: &values, caption: "", unit: "" };
        assert_eq!(k.limit(), 4.0);
        let mut spiky: Vec<f64> = (1..=200).map(f64::from).collect();
        spiky[7] = -1e6;
        let limit = Kymograph { values: &spiky, ..k }.limit();
        assert_eq!(limit, 199.0, "the 99th percentile of 1 … 200 without 8, and 1e6");
        assert_eq!(
            k.runs(),
            vec![(0, 1, 0, 0), (2, 2, 0, -LEVELS), (3, 3, 0, 0), (0, 3, 1, LEVELS)]
        );
    }
}
