//! The run's plots, each as PNG and SVG: force kymographs per axis, the knot's position
//! and the contacts' span against time, the contact counts against time, and (when the run
//! has `internal.csv`) the tension kymograph and the tension at the head against time.

mod figure;
mod kymograph;
mod scatter;
mod time_series;

use std::path::Path;

use plotters::style::RGBColor;

pub use figure::Plot;
use kymograph::Kymograph;
pub use scatter::{IntervalBar, Scatter};
pub use time_series::{Line, TimeSeries};

use crate::colour::Rgb;
use crate::error::ReportError;
use crate::forces::AXES;
use crate::run_dir::RunDir;

/// The x label of the plots against time.
const TIME_LABEL: &str = "time (s)";

/// The plotters colour of `c`.
fn rgb(c: Rgb) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// Draws every plot of `run`; `plots` is the directory their files will go to (named in
/// errors).
pub fn draw(run: &RunDir, plots: &Path) -> Result<Vec<Plot>, ReportError> {
    let mut drawn = Vec::new();
    for (axis, name) in AXES.iter().enumerate() {
        let stem = format!("kymograph_{}", name.to_lowercase());
        let title = format!(
            "Thigmotaxis force kymograph, axis {name} (joint × time, dyn·cm; colours clipped \
             at the 99th percentile of |force|)"
        );
        let caption = format!("Thigmotaxis force, axis {name}");
        let figure = Kymograph {
            times: &run.forces.times,
            joints: run.forces.joints,
            values: &run.forces.values[axis],
            caption: &caption,
            unit: "dyn·cm",
        };
        drawn.push(figure::render(&figure, &stem, &title, &plots.join(format!("{stem}.png")))?);
    }
    if let Some(tension) = &run.tension {
        let stem = "kymograph_tension";
        let title = "Tension along the body (joint × time, dyn, > 0 pulling apart; colours \
                     clipped at the 99th percentile of |tension|)";
        let figure = Kymograph {
            times: &tension.times,
            joints: tension.joints,
            values: &tension.values,
            caption: "Axial tension N at each joint",
            unit: "dyn",
        };
        drawn.push(figure::render(&figure, stem, title, &plots.join(format!("{stem}.png")))?);
        let head = TimeSeries {
            title: "Tension at the head (the pull the body transmits to the wall)".into(),
            x_label: TIME_LABEL.into(),
            y_label: "tension at joint 0 (dyn)".into(),
            times: tension.head_times.clone(),
            lines: vec![Line {
                label: "N at the head".into(),
                colour: [0, 0, 0],
                values: tension.at_head().into_iter().map(Some).collect(),
            }],
        };
        let stem = "tension_head";
        let title = head.title.clone();
        drawn.push(figure::render(&head, stem, &title, &plots.join(format!("{stem}.png")))?);
    }
    let m = &run.metrics;
    let line = |label: &str, colour: Rgb, values: &[Option<f64>]| Line {
        label: label.to_string(),
        colour,
        values: values.to_vec(),
    };
    let knot = TimeSeries {
        title: "Knotted core and contact span".into(),
        x_label: TIME_LABEL.into(),
        y_label: "arc length from the head (cm)".into(),
        times: m.time.clone(),
        lines: vec![
            line("knot core midpoint", [0, 0, 0], &m.knot_position),
            line("knot core start", [99, 99, 99], &m.knot_core_start),
            line("knot core end", [189, 189, 189], &m.knot_core_end),
            line("first contact", [214, 39, 40], &m.first_contact),
            line("last contact", [31, 119, 180], &m.last_contact),
            line("contacts start", [255, 152, 150], &m.contacts_start),
            line("contacts end", [158, 202, 225], &m.contacts_end),
        ],
    };
    let some = |v: &[f64]| v.iter().map(|x| Some(*x)).collect::<Vec<_>>();
    let contacts = TimeSeries {
        title: "Contacts".into(),
        x_label: TIME_LABEL.into(),
        y_label: "count".into(),
        times: m.time.clone(),
        lines: vec![
            line("self contacts", [214, 39, 40], &some(&m.self_contacts)),
            line("wall contacts", [44, 160, 44], &some(&m.wall_contacts)),
        ],
    };
    for (figure, stem) in [(knot, "knot_span"), (contacts, "contacts")] {
        let title = figure.title.clone();
        drawn.push(figure::render(&figure, stem, &title, &plots.join(format!("{stem}.png")))?);
    }
    Ok(drawn)
}

/// Whether `name` is a plot file this module writes (`<stem>.png` or `<stem>.svg`).
pub fn is_own_file(name: &str) -> bool {
    let stem = name.strip_suffix(".png").or_else(|| name.strip_suffix(".svg"));
    stem.is_some_and(|s| {
        s.starts_with("kymograph_") || ["knot_span", "contacts", "tension_head"].contains(&s)
    })
}

/// Writes each plot as `<stem>.png` and `<stem>.svg` into `plots` (created if missing) and
/// returns the files written.
pub fn write(drawn: &[Plot], plots: &Path) -> Result<Vec<std::path::PathBuf>, ReportError> {
    std::fs::create_dir_all(plots).map_err(ReportError::write(plots))?;
    let mut files = Vec::new();
    for plot in drawn {
        for (extension, bytes) in [("png", plot.png.as_slice()), ("svg", plot.svg.as_bytes())] {
            let path = plots.join(format!("{}.{extension}", plot.stem));
            crate::outputs::write_file(&path, bytes)?;
            files.push(path);
        }
    }
    Ok(files)
}

/// Draws each scatter plot and writes it as `<stem>.png` and `<stem>.svg` into `directory`
/// (created if missing); returns the files written.
pub fn write_scatters(
    scatters: &[Scatter],
    directory: &Path,
) -> Result<Vec<std::path::PathBuf>, ReportError> {
    let named = scatters.iter().map(|s| (s.stem.as_str(), s));
    write_figures(named.collect(), directory)
}

/// Draws each line plot (`(stem, plot)`, captioned by its title) and writes it as
/// `<stem>.png` and `<stem>.svg` into `directory` (created if missing); returns the files
/// written.
pub fn write_line_plots(
    plots: &[(String, TimeSeries)],
    directory: &Path,
) -> Result<Vec<std::path::PathBuf>, ReportError> {
    write_figures(plots.iter().map(|(stem, plot)| (stem.as_str(), plot)).collect(), directory)
}

/// Draws the line plot `plot` in memory, named `stem` and captioned by its title; `at` is
/// the file it would be written to, named in errors.
pub fn draw_line_plot(stem: &str, plot: &TimeSeries, at: &Path) -> Result<Plot, ReportError> {
    figure::render(plot, stem, plot.title(), at)
}

/// Renders each `(stem, figure)` and writes it into `directory` ([`write`]).
fn write_figures<F: figure::Figure + Titled>(
    figures: Vec<(&str, &F)>,
    directory: &Path,
) -> Result<Vec<std::path::PathBuf>, ReportError> {
    let drawn = figures
        .into_iter()
        .map(|(stem, f)| figure::render(f, stem, f.title(), &directory.join(format!("{stem}.png"))))
        .collect::<Result<Vec<_>, _>>()?;
    write(&drawn, directory)
}

/// A figure with a caption.
trait Titled {
    /// The caption.
    fn title(&self) -> &str;
}

impl Titled for Scatter {
    fn title(&self) -> &str {
        &self.title
    }
}

impl Titled for TimeSeries {
    fn title(&self) -> &str {
        &self.title
    }
}
