//! # hagfish-report
//!
//! Pictures, a report and exports of a run directory written by `hagfish run`
//! (`docs/outputs.md`), all rendered headless in pure Rust:
//!
//! - `plots/`: force kymographs of the thigmotaxic force field per axis (joint × time),
//!   the knotted core and the contact span against time, contact counts against time; PNG and SVG
//!   (plotters, with an embedded subset of DejaVu Sans).
//! - `animation.gif`: the body as shaded tubes, top and side view (`raster` is a small
//!   software rasteriser with a depth buffer).
//! - `report.html`: one offline page with the summary, the plots, the animation, the
//!   scenario and manifest, and a WebGL view scrubbed by a time slider.
//! - `vtk/`: ParaView legacy polylines per frame with a `.vtk.series` index; `run.glb`:
//!   glTF 2.0 binary, one animated node per body.
//!
//! The required inputs are `centreline.csv`, `metrics.csv` and `forces.csv`;
//! `scenario.ron` (body radii via its biometrics), `manifest.json` and `contacts.csv` are
//! used when present. Every error ([`ReportError`]) names its file, and its line where
//! there is one.

mod animation;
mod centreline;
mod colour;
mod csv;
mod error;
mod font;
mod forces;
mod glb;
mod html;
mod metrics;
mod outputs;
mod plots;
mod radii;
mod raster;
mod run_dir;
mod summary;
mod tension;
#[cfg(test)]
mod test_files;
mod vtk;

pub use centreline::Centreline;
pub use error::ReportError;
pub use forces::{AXES, ThigmoForces};
pub use metrics::Metrics;
pub use outputs::{
    ANIMATION, GLB, PLOTS, REPORT, VTK, Written, own_files, render, report, write_all,
};
pub use radii::{DEFAULT_RADIUS_CM, Radii};
pub use run_dir::RunDir;
pub use tension::Tension;
