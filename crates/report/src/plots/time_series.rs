//! A line plot of several quantities against time (or another shared x, e.g. arc length),
//! with gaps where a value is missing.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::figure::{Axes, DrawResult, Figure, chart};
use super::rgb;
use crate::colour::Rgb;
use crate::font::FAMILY;

/// One line: legend label, colour and one value per frame (`None` leaves a gap).
#[derive(Clone, Debug)]
pub struct Line {
    /// Legend label.
    pub label: String,
    /// Colour.
    pub colour: Rgb,
    /// One value per time.
    pub values: Vec<Option<f64>>,
}

/// Lines against a shared x axis: time, or e.g. arc length for mode shapes.
#[derive(Clone, Debug)]
pub struct TimeSeries {
    /// Caption.
    pub title: String,
    /// Label of the x axis (with its unit), e.g. `time (s)`.
    pub x_label: String,
    /// Label of the y axis.
    pub y_label: String,
    /// The x values, increasing: the times (s) of a time series.
    pub times: Vec<f64>,
    /// The lines.
    pub lines: Vec<Line>,
}

impl TimeSeries {
    /// Smallest and largest value over all lines, widened by 5 % (0..1 with no value).
    fn y_range(&self) -> (f64, f64) {
        let values = self.lines.iter().flat_map(|l| l.values.iter().flatten());
        let (low, high) =
            values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(*v), hi.max(*v)));
        if low > high {
            return (0.0, 1.0);
        }
        let pad = 0.05 * (high - low).max(1.0);
        (low - pad, high + pad)
    }
}

/// The stretches of `values` without gaps, as (time, value) points.
fn segments(times: &[f64], values: &[Option<f64>]) -> Vec<Vec<(f64, f64)>> {
    let mut segments = vec![Vec::new()];
    for (t, v) in times.iter().zip(values) {
        match (v, segments.last_mut()) {
            (Some(v), Some(current)) => current.push((*t, *v)),
            (None, Some(current)) if !current.is_empty() => segments.push(Vec::new()),
            _ => {}
        }
    }
    segments.retain(|s| !s.is_empty());
    segments
}

impl Figure for TimeSeries {
    fn size(&self) -> (u32, u32) {
        (820, 380)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let t0 = self.times.first().copied().unwrap_or(0.0);
        let t1 = self.times.last().copied().filter(|t| *t > t0).unwrap_or(t0 + 1.0);
        let (y0, y1) = self.y_range();
        let axes = Axes {
            title: &self.title,
            title_size: 18,
            x_label: &self.x_label,
            y_label: &self.y_label,
            y_label_area: 56,
        };
        let mut chart = chart(root, &axes, t0..t1, y0..y1)?;
        for line in &self.lines {
            let colour = rgb(line.colour);
            let style = colour.stroke_width(2);
            let mut labelled = None;
            for segment in segments(&self.times, &line.values) {
                labelled = Some(chart.draw_series(LineSeries::new(segment, style))?);
            }
            if let Some(series) = labelled {
                series.label(line.label.as_str()).legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 18, y)], colour.stroke_width(2))
                });
            }
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .label_font((FAMILY, 12))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(160, 160, 160))
            .draw()?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gaps_split_a_line_into_segments() {
        let times = [0.0, 1.0, 2.0, 3.0, 4.0];
        let values = [None, Some(1.0), Some(2.0), None, Some(4.0)];
        assert_eq!(segments(&times, &values), vec![vec![(1.0, 1.0), (2.0, 2.0)], vec![(4.0, 4.0)]]);
        assert!(segments(&times, &[None; 5]).is_empty());
    }

    #[test]
    fn the_y_range_covers_every_value_with_a_margin() {
        let line = |values| Line { label: String::new(), colour: [0, 0, 0], values };
        let mut series = TimeSeries {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            times: vec![0.0, 1.0],
            lines: vec![line(vec![Some(-10.0), None]), line(vec![None, Some(30.0)])],
        };
        assert_eq!(series.y_range(), (-12.0, 32.0));
        series.lines.clear();
        assert_eq!(series.y_range(), (0.0, 1.0));
    }
}
