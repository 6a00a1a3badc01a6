//! # hagfish-report
//!
//! Pictures, a report and exports of a run directory written by `hagfish run`
//! (`docs/outputs.md`), all rendered headless in pure Rust:
//!
//! - `plots/`: force kymographs of the thigmotaxic force field per axis (joint × time),
//!   the knotted core and the contact span against time, contact counts against time; PNG and SVG
//!   (plotters, with an embedded subset of DejaVu Sans).
//! - `animation.gif`: the body as shaded tubes, top and side view (`raster` is a small
//!   software rasteriser with a depth buffer), with the obstacles as wireframes.
//! - `report.html`: one offline page with the summary, the plots, the animation, the
//!   scenario and manifest, and a WebGL view scrubbed by a time slider.
//! - `vtk/`: ParaView legacy polylines per frame with a `.vtk.series` index (and the
//!   obstacles' wireframes); `run.glb`:
//!   glTF 2.0 binary, one animated node per body and a wireframe node per obstacle.
//!
//! The required inputs are `centreline.csv`, `metrics.csv` and `forces.csv`;
//! `scenario.ron` (body radii via its biometrics), `manifest.json` and `contacts.csv` are
//! used when present. Every error ([`ReportError`]) names its file, and its line where
//! there is one.
//!
//! Each output file is read on its own, e.g. the tension the body transmits to the wall per
//! frame, from `internal.csv`:
//!
//! ```
//! let dir = std::env::temp_dir().join(format!("hagfish-report-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir)?;
//! let path = dir.join("internal.csv");
//! std::fs::write(
//!     &path,
//!     "frame,time_s,joint,s_cm,tension_dyn,shear_y_dyn,shear_z_dyn,twist_dyn_cm,\
//!      bend_y_dyn_cm,bend_z_dyn_cm\n0,0,0,0,1.5,0,0,0,0,0\n0,0,1,1,2.5,0,0,0,0,0\n\
//!      1,0.1,0,0,-3,0,0,0,0,0\n1,0.1,1,1,4,0,0,0,0,0\n",
//! )?;
//! let tension = hagfish_report::Tension::read(&path)?;
//! assert_eq!(tension.at_head(), vec![1.5, -3.0]);
//! // A damaged file is an error naming the file and the line.
//! std::fs::write(&path, "frame,time_s,joint,s_cm,tension_dyn\n0,0,x,0,1\n")?;
//! let error = hagfish_report::Tension::read(&path).unwrap_err().to_string();
//! assert!(error.contains("internal.csv") && error.contains('2'), "{error}");
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod animation;
mod around_cylinder;
mod centreline;
mod colour;
mod csv;
mod error;
mod font;
mod forces;
mod frame_selection;
mod glb;
mod html;
mod joint_series;
mod knot_run;
mod loosen_tighten;
mod metrics;
mod metrics_table;
mod obstacles;
mod outputs;
mod plots;
mod radii;
mod raster;
mod run_dir;
mod section;
mod summary;
mod tension;
#[cfg(test)]
mod test_files;
mod vtk;
mod wcon;

pub use around_cylinder::{KnotAroundCylinder, turns_about_axis};
pub use centreline::Centreline;
pub use csv::{CsvFile, MAX_LINE_BYTES, Record, Rows};
pub use error::ReportError;
pub use forces::{AXES, ThigmoForces};
pub use frame_selection::{BODY_FRAME_BUDGET, FrameSelection};
pub use html::escape;
pub use knot_run::{KnotRun, SlideBounds, TABLE_HEADER, signed_percent};
pub use loosen_tighten::LoosenTighten;
pub use metrics::Metrics;
pub use outputs::{
    ANIMATION, GLB, PLOTS, REPORT, VTK, Written, own_files, own_subdirectory, render, report,
    write_all,
};
pub use plots::{
    IntervalBar, Line, Plot, Scatter, TimeSeries, draw_line_plot, write_line_plots, write_scatters,
};
pub use radii::{DEFAULT_RADIUS_CM, Radii};
pub use run_dir::RunDir;
pub use section::Section;
pub use tension::Tension;
pub use wcon::{WCON_FILE, export_wcon, wcon};
