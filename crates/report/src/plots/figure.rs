//! A figure drawn once per backend: to an RGB buffer encoded as PNG, and to SVG text.

use std::ops::Range;
use std::path::Path;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use crate::error::ReportError;
use crate::font::{self, FAMILY};

/// The result of drawing on a plotters area.
pub type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// Something that can draw itself on any plotters backend.
pub trait Figure {
    /// Width and height in pixels.
    fn size(&self) -> (u32, u32);
    /// Draws the figure on `root`, which covers [`Figure::size`].
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB>;
}

/// A chart of f64 against f64 on a plotters backend.
pub type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Axis labels and layout of a chart: [`chart`].
pub struct Axes<'t> {
    /// Caption above the chart.
    pub title: &'t str,
    /// Font size of the caption.
    pub title_size: u32,
    /// Label of the x axis (with its unit).
    pub x_label: &'t str,
    /// Label of the y axis (with its unit).
    pub y_label: &'t str,
    /// Width of the y tick labels' area (pixels).
    pub y_label_area: u32,
}

/// A chart on `root` spanning `x` × `y`, with its caption, a light mesh and the axis labels
/// of `axes` drawn.
pub fn chart<'a, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    axes: &Axes<'_>,
    x: Range<f64>,
    y: Range<f64>,
) -> Result<Chart<'a, DB>, DrawingAreaErrorKind<DB::ErrorType>> {
    let mut chart = ChartBuilder::on(root)
        .caption(axes.title, (FAMILY, axes.title_size))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(axes.y_label_area)
        .build_cartesian_2d(x, y)?;
    chart
        .configure_mesh()
        .light_line_style(RGBColor(235, 235, 235))
        .x_desc(axes.x_label)
        .y_desc(axes.y_label)
        .label_style((FAMILY, 12))
        .axis_desc_style((FAMILY, 14))
        .draw()?;
    Ok(chart)
}

/// A figure rendered both ways.
#[derive(Clone, Debug)]
pub struct Plot {
    /// File stem (`plots/<stem>.png`, `plots/<stem>.svg`).
    pub stem: String,
    /// Caption for the report.
    pub title: String,
    /// PNG bytes.
    pub png: Vec<u8>,
    /// SVG text.
    pub svg: String,
}

/// Renders `figure` as PNG and SVG; `at` names the PNG file for errors.
pub fn render(
    figure: &impl Figure,
    stem: &str,
    title: &str,
    at: &Path,
) -> Result<Plot, ReportError> {
    if !font::register() {
        return Err(ReportError::Draw {
            path: at.to_path_buf(),
            what: "the embedded font is invalid".into(),
        });
    }
    let (width, height) = figure.size();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(ReportError::draw(at))?;
        figure.draw(&root).map_err(ReportError::draw(at))?;
        root.present().map_err(ReportError::draw(at))?;
    }
    let mut rgb = vec![255u8; 3 * width as usize * height as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        figure.draw(&root).map_err(ReportError::draw(at))?;
        root.present().map_err(ReportError::draw(at))?;
    }
    let png = encode_png(&rgb, width, height).map_err(ReportError::draw(at))?;
    Ok(Plot { stem: stem.to_string(), title: title.to_string(), png, svg })
}

/// PNG bytes of an 8-bit RGB image.
fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>, png::EncodingError> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header()?;
    writer.write_image_data(rgb)?;
    writer.finish()?;
    Ok(bytes)
}
