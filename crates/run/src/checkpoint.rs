//! Checkpoints: everything a run carries from one step to the next, so that a stopped run
//! continues bit for bit (`docs/outputs.md`).
//!
//! A step depends on the state (t, q, q̇), the controller's state (phase, its start, the
//! forming script's progress), the step counter (it only labels reports) and the velocity
//! solve's warm start: the active-set method starts from the previous step's multipliers,
//! and a different start can end in a different rounding of the same answer, so they are
//! saved too. Everything else in the step data is recomputed from the state at the start of
//! every step. Floating-point vectors are stored as the hexadecimal bits of each value, so
//! they come back exactly.

use std::fmt::Write as _;
use std::path::Path;

use hagfish_anatomy::DataFile;
use hagfish_control::ControllerState;
use hagfish_tree::State;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::error::RunError;
use crate::recorder::RecordedFile;
use hagfish_scenario::ScenarioError;
use hagfish_sim::{IntervalMaxima, KeyedMultiplier, RowKey, fnv1a64};

/// Name of the checkpoint file in a run directory.
pub const CHECKPOINT_FILE: &str = "checkpoint.ron";

/// Version of the checkpoint format (2: body hash, substep counts and the checksum line; 3: the
/// warm start by what each row constrains instead of by row position).
pub const CHECKPOINT_FORMAT: u32 = 3;

/// The first line of a checkpoint file: a RON comment with the FNV-1a hash of the rest.
const CHECKSUM_PREFIX: &str = "// fnv1a64 ";

/// f64 values stored exactly: the 16 hexadecimal digits of each value's bits, separated by
/// spaces.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ExactF64s(pub Vec<f64>);

impl Serialize for ExactF64s {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut words = String::with_capacity(17 * self.0.len());
        for (k, v) in self.0.iter().enumerate() {
            let separator = if k == 0 { "" } else { " " };
            // Writing to a `String` cannot fail.
            let _ = write!(words, "{separator}{:016x}", v.to_bits());
        }
        serializer.serialize_str(&words)
    }
}

impl<'de> Deserialize<'de> for ExactF64s {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = String::deserialize(deserializer)?;
        text.split_whitespace()
            .map(|word| {
                u64::from_str_radix(word, 16).map(f64::from_bits).map_err(|_| {
                    serde::de::Error::custom(format!("`{word}` is not 16 hexadecimal digits"))
                })
            })
            .collect::<Result<_, _>>()
            .map(ExactF64s)
    }
}

/// A checkpoint's format alone (its other fields are ignored), read before the rest.
#[derive(Deserialize)]
struct FormatOnly {
    format: u32,
}

/// The velocity solve's warm start as a checkpoint keeps it (`hagfish_sim::WarmStart`): for each
/// row of the last solve, its group and ordinal, and exactly its place and multiplier.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CarriedMultipliers {
    /// (group, ordinal) of each row ([`RowKey`]).
    pub rows: Vec<(u8, u32)>,
    /// place₀, place₁ and λ of each row, three values a row.
    pub values: ExactF64s,
}

impl CarriedMultipliers {
    /// The checkpoint's form of `multipliers`.
    pub fn new(multipliers: &[KeyedMultiplier]) -> Self {
        let rows = multipliers.iter().map(|m| (m.key.group, m.key.ordinal)).collect();
        let values =
            multipliers.iter().flat_map(|m| [m.key.place[0], m.key.place[1], m.lambda]).collect();
        CarriedMultipliers { rows, values: ExactF64s(values) }
    }

    /// The multipliers back, or `None` when the values are not three a row.
    pub fn multipliers(&self) -> Option<Vec<KeyedMultiplier>> {
        if self.values.0.len() != 3 * self.rows.len() {
            return None;
        }
        let values = self.values.0.chunks_exact(3);
        let keyed = self.rows.iter().zip(values).map(|(&(group, ordinal), v)| KeyedMultiplier {
            key: RowKey { group, ordinal, place: [v[0], v[1]] },
            lambda: v[2],
        });
        Some(keyed.collect())
    }
}

/// The saved run: enough to continue it exactly, and the lengths of its output files at the
/// frame it was taken.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Checkpoint {
    /// [`CHECKPOINT_FORMAT`].
    pub format: u32,
    /// Hash of the resolved scenario ([`hagfish_scenario::LoadedScenario::hash`]), to refuse
    /// another's.
    pub scenario_hash: String,
    /// Hash of the body file's bytes ([`hagfish_scenario::LoadedScenario::body_hash`]), to
    /// refuse a resume after the body file was edited.
    pub body_hash: String,
    /// Hash of the files the phases read
    /// ([`hagfish_scenario::LoadedScenario::referenced_files_hash`]), to refuse a resume after a
    /// knot plan, template, modal basis or replay was edited; `None` in
    /// checkpoints written before it existed (nothing to compare then).
    #[serde(default)]
    pub referenced_files_hash: Option<String>,
    /// Frames recorded (the next frame's index).
    pub frames: usize,
    /// Steps taken.
    pub steps: u64,
    /// Simulation time t (s).
    pub t: ExactF64s,
    /// Joint angles q (rad).
    pub q: ExactF64s,
    /// Joint rates q̇ (rad/s).
    pub qdot: ExactF64s,
    /// Multipliers of the last velocity solve by what their rows constrain (the next solve's
    /// warm start).
    pub warm_start: CarriedMultipliers,
    /// The controller's state.
    pub controller: ControllerState,
    /// Worst penetrations and limit excess of the run so far.
    pub maxima: IntervalMaxima,
    /// Steps taken as substeps so far ([`crate::RunSummary::substepped_steps`]).
    pub substepped_steps: u64,
    /// The most substeps of one step so far.
    pub max_substeps: u32,
    /// Steps retried with contacts at the chain's resolution so far
    /// ([`crate::RunSummary::resolved_steps`]; 0 in checkpoints written before it existed).
    #[serde(default)]
    pub resolved_steps: u64,
    /// Output files and their lengths at this frame (empty when not written by a recorder).
    pub files: Vec<RecordedFile>,
}

impl Checkpoint {
    /// The saved state.
    pub fn state(&self) -> State {
        State {
            t: self.t.0.first().copied().unwrap_or(0.0),
            q: self.q.0.clone(),
            qdot: self.qdot.0.clone(),
        }
    }

    /// Reads a checkpoint: its first line must hold the checksum of the rest (any changed or
    /// lost byte is refused), then the RON is parsed (errors at their `file:line:column`).
    pub fn read(path: &Path) -> Result<Self, RunError> {
        let refuse = |reason: String| RunError::Checkpoint { path: path.to_path_buf(), reason };
        let bytes = hagfish_anatomy::read_bounded(path, hagfish_anatomy::MAX_DATA_FILE_BYTES)
            .map_err(|e| refuse(e.to_string()))?;
        let (first, rest) = match bytes.iter().position(|&b| b == b'\n') {
            Some(end) => (&bytes[..end], &bytes[end + 1..]),
            None => (&bytes[..], &[][..]),
        };
        let expected = format!("{CHECKSUM_PREFIX}{:016x}", fnv1a64(rest));
        if first != expected.as_bytes() {
            return Err(refuse(
                "checksum mismatch: the content after the first line is not what its recorded \
                 checksum covers; the file was changed or damaged after it was written"
                    .to_owned(),
            ));
        }
        // The format first, so that another format's fields are refused as that, not as a parse
        // error on them.
        let format = DataFile::<FormatOnly>::parse(&bytes, path).map_err(ScenarioError::from)?;
        if format.value.format != CHECKPOINT_FORMAT {
            return Err(refuse(format!(
                "format {} (this build reads format {CHECKPOINT_FORMAT}: since decision 0036 the \
                 warm start is kept by what each row constrains, which a checkpoint of format \
                 2 does not hold); run the scenario again from its start",
                format.value.format
            )));
        }
        let checkpoint =
            DataFile::<Checkpoint>::parse(&bytes, path).map_err(ScenarioError::from)?.value;
        if checkpoint.t.0.len() != 1 {
            return Err(refuse(format!("{} time values (expected one)", checkpoint.t.0.len())));
        }
        Ok(checkpoint)
    }

    /// Writes the checkpoint to `path` atomically: to a temporary file beside it, then renamed
    /// over it, so a killed run leaves either the old or the new checkpoint.
    pub fn write(&self, path: &Path) -> Result<(), RunError> {
        let fail = |source| RunError::Output { path: path.to_path_buf(), source };
        // Every string of a checkpoint (hash, hexadecimal words, file names) is plain ASCII
        // without quotes or backslashes, which RON writes alike escaped or not; not escaping
        // spares a pass over every character.
        let config = ron::ser::PrettyConfig::default().escape_strings(false);
        let text =
            ron::ser::to_string_pretty(self, config).map_err(|e| fail(std::io::Error::other(e)))?;
        let file = format!("{CHECKSUM_PREFIX}{:016x}\n{text}", fnv1a64(text.as_bytes()));
        crate::output_file::replace_file(path, file.as_bytes())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_checkpoint_comes_back_bit_for_bit() -> Result<(), RunError> {
        let awkward = vec![0.1, -0.0, f64::MIN_POSITIVE, 1.0 / 3.0, f64::MAX, f64::NAN];
        let checkpoint = Checkpoint {
            format: CHECKPOINT_FORMAT,
            scenario_hash: "0123456789abcdef".into(),
            body_hash: "fedcba9876543210".into(),
            referenced_files_hash: Some(String::new()),
            frames: 7,
            steps: 70,
            t: ExactF64s(vec![0.7000000000000005]),
            q: ExactF64s(awkward.clone()),
            qdot: ExactF64s(awkward.iter().map(|v| -v).collect()),
            warm_start: CarriedMultipliers::default(),
            controller: ControllerState::default(),
            maxima: IntervalMaxima { self_penetration: 0.1 + 0.2, ..IntervalMaxima::default() },
            substepped_steps: 3,
            max_substeps: 4,
            resolved_steps: 2,
            files: vec![RecordedFile {
                name: "q.npy".into(),
                bytes: 128,
                fnv1a64: Some("cbf29ce484222325".into()),
            }],
        };
        let dir = std::env::temp_dir().join(format!("hagfish-checkpoint-{}", std::process::id()));
        std::fs::create_dir_all(&dir)
            .map_err(|source| RunError::Output { path: dir.clone(), source })?;
        let path = dir.join(CHECKPOINT_FILE);
        checkpoint.write(&path)?;
        let back = Checkpoint::read(&path)?;
        let bits = |v: &ExactF64s| v.0.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&back.q), bits(&checkpoint.q));
        assert_eq!(bits(&back.qdot), bits(&checkpoint.qdot));
        assert_eq!(back.state().t.to_bits(), 0.7000000000000005f64.to_bits());
        assert_eq!(back.maxima, checkpoint.maxima);
        assert_eq!(back.files, checkpoint.files);
        std::fs::remove_dir_all(&dir).map_err(|source| RunError::Output { path: dir, source })?;
        Ok(())
    }
}
