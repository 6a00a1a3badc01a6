//! # hagfish-run
//!
//! Running a scenario of the hagfish simulator (`docs/architecture.md`). **Invariant: a loaded
//! scenario in; frames, checkpoints and a summary out — and a run resumed from any of its
//! checkpoints records exactly what the uninterrupted run does.** [`run`] steps the world of a
//! [`hagfish_scenario::LoadedScenario`] ([`hagfish_sim::World::advance`], retries included),
//! analyses the knot, lets the controller observe it, and hands every frame and then its
//! [`Checkpoint`] to a [`FrameSink`]: the [`Recorder`] writes them as the files of a run
//! directory (CSV, `.npy`, `checkpoint.ron`; `docs/outputs.md`).
//!
//! ```
//! use hagfish_run::{Frame, FrameSink, RunEnd, RunError, RunOptions, run};
//! use hagfish_scenario::LoadedScenario;
//!
//! /// Keeps the time of every frame.
//! struct Times(Vec<f64>);
//! impl FrameSink for Times {
//!     fn record(&mut self, frame: &Frame<'_>) -> Result<(), RunError> {
//!         self.0.push(frame.time);
//!         Ok(())
//!     }
//! }
//!
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/scenarios/tie.ron");
//! let loaded = LoadedScenario::load(path)?;
//! let options = RunOptions { stop_after_frame: Some(3), ..RunOptions::default() };
//! let mut times = Times(Vec::new());
//! let outcome = run(&loaded, options, &mut times, &mut |_| {})?;
//! assert!(matches!(outcome.end, RunEnd::Interrupted));
//! assert_eq!(times.0.len(), 4, "frames 0 to 3, one every 0.1 s");
//! # Ok::<(), hagfish_run::RunError>(())
//! ```

mod checkpoint;
mod csv_text;
mod error;
mod force_columns;
mod force_field;
mod knot_core;
pub mod npy;
mod npz;
mod output_file;
mod recorder;
mod run;
mod scientific;

pub use checkpoint::{
    CHECKPOINT_FILE, CHECKPOINT_FORMAT, CarriedMultipliers, Checkpoint, ExactF64s,
};
pub use csv_text::csv_record;
pub use error::RunError;
pub use force_field::{ForceFieldLog, ForceFieldStats};
pub use hagfish_sim::dof_arc_lengths;
pub use knot_core::KnotCore;
pub use npz::{NpyData, NpzEntry, npz_bytes, write_npz};
pub use output_file::replace_file;
pub use recorder::{
    CENTRELINE_HEADER, CONTACTS_HEADER, FORCES_HEADER, Frame, FrameSink, METRICS_HEADER,
    RecordedFile, Recorder,
};
pub use run::{
    DEFAULT_MAX_STEPS, KnotSample, PreparedRun, Progress, RunEnd, RunOptions, RunOutcome,
    RunSummary, run,
};
