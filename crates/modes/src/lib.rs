//! # hagfish-modes
//!
//! The modes of a run's thigmotaxic force field (`thigmo_force.npy`, frames × DOFs): a
//! proper orthogonal decomposition F = U Σ Vᵀ (faer's thin SVD) of the frames of one phase and
//! the DOFs of one kind, with each mode's energy σᵢ²/Σσ², the mode shapes along the body (cm
//! and s/L), their time courses σᵢuᵢ(t), a travelling-wave test of the dominant pair against
//! the knot's speed, principal angles between bases of different runs and the energy of one
//! run's field that another run's modes capture (thesis §7.2: a reduced basis for the muscle
//! controls that slide the knot; `docs/physics.md`, "Modes of the force field").
//! `hagfish modes RUN_DIR` writes them into `RUN_DIR/modes/` (CSV, JSON, `modes.npz`, plots),
//! `hagfish modes RUN_DIR --against OTHER` the comparison into `RUN_DIR/modes/against.json`.

mod against;
mod angles;
mod arrays;
mod error;
mod field;
mod line_fit;
mod output;
mod pod;
mod replay;
mod report_section;
mod run_field;
mod wave;

pub use against::{AGAINST_FILE, Comparison, GRID_POINTS, write_against};
pub use angles::{captured_energy, principal_angles, resample, uniform_grid};
pub use arrays::{NPZ_FILE, write_npz};
pub use error::ModesError;
pub use field::Field;
pub use hagfish_control::{DofKind, KindSelection};
pub use line_fit::{LineFit, fit_line, unwrap};
pub use output::{Decomposition, MODES_DIR, write_outputs};
pub use pod::{ENERGY_LEVELS, Pod};
pub use replay::{replay_values, write_replay};
pub use report_section::{SECTION_ID, SECTION_TITLE, report_section, report_sections};
pub use run_field::RunField;
pub use wave::{AMPLITUDE_THRESHOLD, WaveFit};
