//! A scatter plot of one quantity against another: a sweep's summary metric against a swept
//! parameter, one point per run, and where the runs are replicated each grid point's mean
//! with its confidence interval drawn as an error bar.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::figure::{Axes, DrawResult, Figure, chart};

/// Points of one quantity (y) against another (x).
#[derive(Clone, Debug, PartialEq)]
pub struct Scatter {
    /// File stem (`<stem>.png`, `<stem>.svg`).
    pub stem: String,
    /// Caption.
    pub title: String,
    /// Label of the x axis (with its unit).
    pub x_label: String,
    /// Label of the y axis (with its unit).
    pub y_label: String,
    /// The points (x, y).
    pub points: Vec<(f64, f64)>,
    /// Intervals drawn over the points (none for a plain scatter).
    pub intervals: Vec<IntervalBar>,
}

/// A mean and its confidence interval at one x, drawn as a dark marker with a vertical bar.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntervalBar {
    /// Where (x).
    pub x: f64,
    /// The mean (y).
    pub mean: f64,
    /// The interval's lower end (y).
    pub low: f64,
    /// The interval's upper end (y).
    pub high: f64,
}

/// Smallest and largest of `values`, widened by 5 % of the range (by 0.5 if all are equal;
/// 0..1 without values).
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (low, high) =
        values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    if low > high {
        return (0.0, 1.0);
    }
    let pad = if high > low { 0.05 * (high - low) } else { 0.5 * low.abs().max(1.0) };
    (low - pad, high + pad)
}

impl Figure for Scatter {
    fn size(&self) -> (u32, u32) {
        (560, 400)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let bars = &self.intervals;
        let (x0, x1) = range(self.points.iter().map(|p| p.0).chain(bars.iter().map(|b| b.x)));
        let ends = bars.iter().flat_map(|b| [b.low, b.high]);
        let (y0, y1) = range(self.points.iter().map(|p| p.1).chain(ends));
        let axes = Axes {
            title: &self.title,
            title_size: 16,
            x_label: &self.x_label,
            y_label: &self.y_label,
            y_label_area: 60,
        };
        let mut chart = chart(root, &axes, x0..x1, y0..y1)?;
        let colour = RGBColor(31, 119, 180);
        if bars.is_empty() {
            chart.draw_series(self.points.iter().map(|&p| Circle::new(p, 4, colour.filled())))?;
            return Ok(());
        }
        let runs = RGBColor(158, 202, 225);
        chart.draw_series(self.points.iter().map(|&p| Circle::new(p, 3, runs.filled())))?;
        let style = ShapeStyle::from(&BLACK).stroke_width(2);
        chart.draw_series(
            bars.iter().map(|b| ErrorBar::new_vertical(b.x, b.low, b.mean, b.high, style, 8)),
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ranges_cover_every_point_and_a_single_value_gets_width() {
        assert_eq!(range([0.0, 10.0].into_iter()), (-0.5, 10.5));
        assert_eq!(range([2.0, 2.0].into_iter()), (1.0, 3.0));
        assert_eq!(range(std::iter::empty()), (0.0, 1.0));
    }
}
