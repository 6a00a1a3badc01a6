//! Writes a run's outputs as it goes, flushing every frame, so a killed run keeps every
//! completed frame (`docs/outputs.md` describes the files and their columns).
//!
//! - `centreline.csv`: `frame,time_s,body,x_cm,y_cm,z_cm`, one row per body per frame.
//! - `metrics.csv`: one row per frame (see [`METRICS_HEADER`]).
//! - `forces.csv`: `frame,time_s,joint,axis,group,value_dyn_cm`, per DOF and recorded group.
//! - `contacts.csv`: one row per self contact per frame (see [`CONTACTS_HEADER`]).
//! - `internal.csv`: one row per joint per frame, the load it transmits (see
//!   [`INTERNAL_HEADER`]).
//! - `q.npy`, `qdot.npy`, `thigmo_force.npy`: frames × DOFs (f64, see `npy.rs`);
//!   `internal.npy`: frames × (joints · 6), the columns of `internal.csv` per joint.
//! - `checkpoint.ron`: the latest frame's [`Checkpoint`], replaced atomically.

use std::path::{Path, PathBuf};

use glam::DVec3;
use hagfish_control::KnotSpan;
use hagfish_geometry::{Centreline, SelfContact};
use hagfish_knots::KnotReport;
use hagfish_tree::State;
use serde::{Deserialize, Serialize};

use crate::checkpoint::{CHECKPOINT_FILE, Checkpoint};
use crate::csv_text::CsvText;
use crate::error::RunError;
use crate::force_columns::ForceColumns;
use crate::knot_core::KnotCore;
use crate::npy::{NpyWriter, rows_hash};
use crate::output_file::OutputFile;
use crate::scientific::Scientific;
use hagfish_sim::StepReport;
use hagfish_sim::{DofLabel, GroupForces, RECORDED_GROUPS};
use hagfish_sim::{GripLoad, IntervalMaxima, JointLoad};

/// Header of `forces.csv`: generalized constraint forces per joint, axis and group, averaged
/// over the steps since the previous frame (dyn·cm).
pub const FORCES_HEADER: &str = "frame,time_s,joint,axis,group,value_dyn_cm";

/// Header of `centreline.csv`.
pub const CENTRELINE_HEADER: &str = "frame,time_s,body,x_cm,y_cm,z_cm";

/// Header of `metrics.csv`. Contact, solver and grip columns describe the step that ended at
/// the frame (contacts measured at its start); penetration and limit columns are maxima over
/// the steps since the previous frame; knot columns describe the frame's centreline.
pub const METRICS_HEADER: &str = "frame,time_s,phase,self_contacts,wall_contacts,\
knot,knot_agreement,knot_first_body,knot_last_body,knot_position_cm,\
knot_core_start_cm,knot_core_end_cm,knot_core_length_cm,\
knot_core_start_L,knot_core_mid_L,knot_core_length_L,knot_core_length_D,knot_writhe,\
max_self_penetration_cm,max_self_penetration_rel,max_skin_compression,max_wall_penetration_cm,max_limit_excess_deg,\
contacts_start_cm,contacts_end_cm,first_contact_cm,last_contact_cm,\
contact_span_cm,contact_midpoint_cm,solver_path,solver_status,solver_iterations,slack_rows,slack_max_cm_s,\
grip_x_cm,grip_y_cm,grip_z_cm,grip_force_x_dyn,grip_force_y_dyn,grip_force_z_dyn";

/// Header of `contacts.csv`: the self contacts of the step that ended at the frame (detected
/// at its start): spline parameters, arc lengths from the head, gap and the two points.
pub const CONTACTS_HEADER: &str = "frame,time_s,contact,u_a,u_b,arc_a_cm,arc_b_cm,gap_cm,\
a_x_cm,a_y_cm,a_z_cm,b_x_cm,b_y_cm,b_z_cm";

/// Header of `internal.csv`: the load each joint transmits in the step that ended at the
/// frame ([`JointLoad`]): joint index, its arc length from the head, the force and moment
/// of the tail-ward part on the head-ward part in the frame of the body after the joint.
pub const INTERNAL_HEADER: &str = "frame,time_s,joint,s_cm,tension_dyn,shear_y_dyn,shear_z_dyn,\
twist_dyn_cm,bend_y_dyn_cm,bend_z_dyn_cm";

/// Where a run's frames go: files ([`Recorder`]) or memory (tests).
pub trait FrameSink {
    /// Takes one frame.
    fn record(&mut self, frame: &Frame<'_>) -> Result<(), RunError>;

    /// Takes the checkpoint of the frame just recorded (files keep it; memory sinks need not).
    fn checkpoint(&mut self, _checkpoint: &mut Checkpoint) -> Result<(), RunError> {
        Ok(())
    }
}

/// What one frame records.
#[derive(Clone, Copy, Debug)]
pub struct Frame<'a> {
    /// Frame index (0 = initial state).
    pub index: usize,
    /// Simulation time (s).
    pub time: f64,
    /// Name of the controller phase.
    pub phase: &'a str,
    /// The state at the frame.
    pub state: &'a State,
    /// Body centres (cm).
    pub centres: &'a [DVec3],
    /// The report of the step that ended at this frame (default for frame 0).
    pub step: &'a StepReport,
    /// Worst values since the previous frame.
    pub maxima: &'a IntervalMaxima,
    /// Knot analysis of the centreline, if it succeeded.
    pub knot: Option<&'a KnotReport>,
    /// Body radii (cm), head to tail, for the knotted core's local diameter.
    pub radii: &'a [f64],
    /// The body length L (cm), for the knotted core's fractions.
    pub body_length_cm: f64,
    /// The stretch of body the self contacts span (of the step that ended at the frame).
    pub span: Option<KnotSpan>,
    /// Self contacts of the step that ended at the frame (none for frame 0).
    pub contacts: &'a [SelfContact],
    /// The centreline those contacts were found on (for arc lengths).
    pub centreline: &'a Centreline,
    /// Labels of the DOFs (joint, axis).
    pub labels: &'a [DofLabel],
    /// Generalized constraint forces averaged over the steps since the previous frame.
    pub forces: &'a GroupForces,
    /// The load each joint transmitted in the step that ended at the frame (zeros for frame
    /// 0).
    pub internal: &'a [JointLoad],
    /// The grip's pull in the step that ended at the frame, if a grip held the tail end.
    pub grip: Option<GripLoad>,
}

/// An output file and its length in bytes at a checkpoint.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordedFile {
    /// File name inside the run directory.
    pub name: String,
    /// Length (bytes).
    pub bytes: u64,
    /// For an `.npy` array: the FNV-1a 64 hash of its rows' bytes (16 hex digits), checked on
    /// resume (absent in checkpoints written before it existed, and for CSV files).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fnv1a64: Option<String>,
}

/// The open output files of a run.
#[derive(Debug)]
pub struct Recorder {
    directory: PathBuf,
    centreline: OutputFile,
    metrics: OutputFile,
    forces: OutputFile,
    contacts: OutputFile,
    internal: OutputFile,
    q: NpyWriter,
    qdot: NpyWriter,
    thigmo: NpyWriter,
    internal_npy: NpyWriter,
    force_columns: ForceColumns,
}

/// The CSV files and their headers, in the order of [`Recorder::files`].
const CSV_FILES: [(&str, &str); 5] = [
    ("centreline.csv", CENTRELINE_HEADER),
    ("metrics.csv", METRICS_HEADER),
    ("forces.csv", FORCES_HEADER),
    ("contacts.csv", CONTACTS_HEADER),
    ("internal.csv", INTERNAL_HEADER),
];

/// The `.npy` files, in the order of [`Recorder::files`].
const NPY_FILES: [&str; 4] = ["q.npy", "qdot.npy", "thigmo_force.npy", "internal.npy"];

/// Values per joint in `internal.npy` (the six load columns of `internal.csv`).
pub const INTERNAL_VALUES_PER_JOINT: usize = 6;

impl Recorder {
    /// The names of the files a recorder writes in its directory.
    pub const FILE_NAMES: [&str; 9] = [
        CSV_FILES[0].0,
        CSV_FILES[1].0,
        CSV_FILES[2].0,
        CSV_FILES[3].0,
        CSV_FILES[4].0,
        NPY_FILES[0],
        NPY_FILES[1],
        NPY_FILES[2],
        NPY_FILES[3],
    ];

    /// The columns of each `.npy` file for `dofs` DOFs and `joints` joints.
    fn npy_columns(dofs: usize, joints: usize) -> [usize; 4] {
        [dofs, dofs, dofs, INTERNAL_VALUES_PER_JOINT * joints]
    }

    /// Creates `directory` (and parents) and the output files (CSV with their headers, `.npy`
    /// with `dofs` columns, or six per joint, and no rows).
    pub fn create(directory: &Path, dofs: usize, joints: usize) -> Result<Self, RunError> {
        std::fs::create_dir_all(directory)
            .map_err(|source| RunError::Output { path: directory.to_path_buf(), source })?;
        let csv = |(name, header): (&str, &str)| -> Result<OutputFile, RunError> {
            let mut file = OutputFile::create(&directory.join(name))?;
            file.line(format_args!("{header}"))?;
            file.flush()?;
            Ok(file)
        };
        let csv = CSV_FILES.map(csv);
        let columns = Self::npy_columns(dofs, joints);
        let npy =
            std::array::from_fn(|k| NpyWriter::create(&directory.join(NPY_FILES[k]), columns[k]));
        Self::from_files(directory, csv, npy)
    }

    /// Reopens the output files in `directory` as they were at `checkpoint`: every file is cut
    /// to its length then (dropping frames recorded after it) and appended to.
    pub fn reopen(
        directory: &Path,
        dofs: usize,
        joints: usize,
        checkpoint: &Checkpoint,
    ) -> Result<Self, RunError> {
        let length = |name: &str| {
            checkpoint.files.iter().find(|f| f.name == name).map(|f| f.bytes).ok_or_else(|| {
                RunError::Checkpoint {
                    path: directory.join(CHECKPOINT_FILE),
                    reason: format!("no length of {name}"),
                }
            })
        };
        // The arrays are checked against the checkpoint's hashes before any file is cut.
        let frames = checkpoint.frames;
        let columns = Self::npy_columns(dofs, joints);
        let mut hashes = [0; 4];
        for (k, name) in NPY_FILES.iter().enumerate() {
            let recorded = checkpoint.files.iter().find(|f| f.name == *name);
            let expected = recorded.and_then(|f| f.fnv1a64.as_deref());
            hashes[k] = rows_hash(&directory.join(name), columns[k], frames, expected)?;
        }
        let csv = CSV_FILES.map(|(name, _)| {
            length(name).and_then(|l| OutputFile::reopen(&directory.join(name), l))
        });
        let npy = std::array::from_fn(|k| {
            NpyWriter::reopen(&directory.join(NPY_FILES[k]), columns[k], frames, hashes[k])
        });
        Self::from_files(directory, csv, npy)
    }

    /// The recorder of `directory` from its opened CSV files (in [`CSV_FILES`] order) and
    /// `.npy` writers (in [`NPY_FILES`] order), or the first error among them.
    fn from_files(
        directory: &Path,
        csv: [Result<OutputFile, RunError>; 5],
        npy: [Result<NpyWriter, RunError>; 4],
    ) -> Result<Self, RunError> {
        let [centreline, metrics, forces, contacts, internal] = csv;
        let [q, qdot, thigmo, internal_npy] = npy;
        Ok(Self {
            directory: directory.to_path_buf(),
            centreline: centreline?,
            metrics: metrics?,
            forces: forces?,
            contacts: contacts?,
            internal: internal?,
            q: q?,
            qdot: qdot?,
            thigmo: thigmo?,
            internal_npy: internal_npy?,
            force_columns: ForceColumns::default(),
        })
    }

    /// Every output file with its current length.
    pub fn files(&self) -> Vec<RecordedFile> {
        let csv = [&self.centreline, &self.metrics, &self.forces, &self.contacts, &self.internal]
            .map(|f| RecordedFile { name: file_name(f.path()), bytes: f.len(), fnv1a64: None });
        let npy = [&self.q, &self.qdot, &self.thigmo, &self.internal_npy].map(|f| RecordedFile {
            name: file_name(f.path()),
            bytes: f.len(),
            fnv1a64: Some(f.rows_hash()),
        });
        csv.into_iter().chain(npy).collect()
    }

    fn write_centreline(&mut self, frame: &Frame<'_>, prefix: &str) -> Result<(), RunError> {
        for (body, c) in frame.centres.iter().enumerate() {
            self.centreline
                .line(format_args!("{prefix},{body},{:.6},{:.6},{:.6}", c.x, c.y, c.z))?;
        }
        Ok(())
    }

    fn write_metrics(&mut self, frame: &Frame<'_>, prefix: &str) -> Result<(), RunError> {
        let (knot, agreement, first, last, position) = match frame.knot {
            Some(k) => (
                k.knot.to_string(),
                format!("{:.3}", k.agreement),
                k.extent.map_or(String::new(), |e| e.0.to_string()),
                k.extent.map_or(String::new(), |e| e.1.to_string()),
                k.position.map_or(String::new(), |p| format!("{p:.3}")),
            ),
            None => Default::default(),
        };
        let core = frame
            .knot
            .and_then(|k| KnotCore::of(k, frame.centres, frame.radii, frame.body_length_cm))
            .map_or(",,,,,,".to_string(), |c| {
                format!(
                    "{:.3},{:.3},{:.3},{:.4},{:.4},{:.4},{:.3}",
                    c.start_cm,
                    c.end_cm,
                    c.length_cm(),
                    c.of_body_length(c.start_cm),
                    c.of_body_length(c.midpoint_cm()),
                    c.of_body_length(c.length_cm()),
                    c.length_in_diameters()
                )
            });
        let writhe = frame.knot.and_then(|k| k.writhe).map_or(String::new(), |w| format!("{w:.3}"));
        let (s, m) = (frame.step, frame.maxima);
        let span = frame.span.map_or(",,,,,".to_string(), |k| {
            format!(
                "{:.3},{:.3},{:.3},{:.3},{:.3},{:.3}",
                k.start_cm,
                k.end_cm,
                k.first_contact_cm,
                k.last_contact_cm,
                k.length_cm(),
                k.midpoint_cm()
            )
        });
        let grip = frame.grip.map_or(",,,,,".to_string(), |g| {
            let [x, y, z] = g.point.to_array();
            let [fx, fy, fz] = g.force.to_array();
            format!("{x:.6},{y:.6},{z:.6},{fx:.6e},{fy:.6e},{fz:.6e}")
        });
        self.metrics.line(format_args!(
            "{prefix},{},{},{},{knot},{agreement},{first},{last},{position},{core},{writhe},{:.6},{:.6},{:.6},{:.6},{:.4},{span},{:?},{:?},{},{},{:.3e},{grip}",
            CsvText(frame.phase),
            s.self_contacts,
            s.wall_contacts,
            m.self_penetration,
            m.self_penetration_relative,
            m.skin_compression,
            m.wall_penetration,
            m.limit_excess.to_degrees(),
            s.solve.path,
            s.solve.status,
            s.solve.iterations,
            s.solve.slack.count,
            s.solve.slack.max,
        ))
    }

    fn write_forces(&mut self, frame: &Frame<'_>, prefix: &str) -> Result<(), RunError> {
        let columns = self.force_columns.for_labels(frame.labels);
        for (values, columns) in frame.forces.values.iter().zip(columns) {
            for (columns, value) in columns.iter().zip(values) {
                self.forces.bytes(prefix.as_bytes());
                self.forces.bytes(columns.as_bytes());
                self.forces.line(format_args!("{}", Scientific(*value)))?;
            }
        }
        Ok(())
    }

    fn write_contacts(&mut self, frame: &Frame<'_>, prefix: &str) -> Result<(), RunError> {
        for (k, c) in frame.contacts.iter().enumerate() {
            let (a, b) = (c.point_a, c.point_b);
            self.contacts.line(format_args!(
                "{prefix},{k},{:.6},{:.6},{:.4},{:.4},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}",
                c.u_a,
                c.u_b,
                frame.centreline.arc_length(c.u_a),
                frame.centreline.arc_length(c.u_b),
                c.gap,
                a.x,
                a.y,
                a.z,
                b.x,
                b.y,
                b.z,
            ))?;
        }
        Ok(())
    }
}

/// The six values of a load in the column order of [`INTERNAL_HEADER`].
fn load_values(load: &JointLoad) -> [f64; INTERNAL_VALUES_PER_JOINT] {
    [
        load.tension_dyn,
        load.shear_y_dyn,
        load.shear_z_dyn,
        load.twist_dyn_cm,
        load.bend_y_dyn_cm,
        load.bend_z_dyn_cm,
    ]
}

impl Recorder {
    fn write_internal(&mut self, frame: &Frame<'_>, prefix: &str) -> Result<(), RunError> {
        let spacing = frame.body_length_cm / frame.internal.len().max(1) as f64;
        for (joint, load) in frame.internal.iter().enumerate() {
            let [n, sy, sz, t, my, mz] = load_values(load).map(Scientific);
            let s = joint as f64 * spacing;
            self.internal
                .line(format_args!("{prefix},{joint},{s:.4},{n},{sy},{sz},{t},{my},{mz}"))?;
        }
        Ok(())
    }
}

impl FrameSink for Recorder {
    /// Appends one frame to every file, each file's rows in one write. Every CSV row starts
    /// with the frame's index and time, formatted once.
    fn record(&mut self, frame: &Frame<'_>) -> Result<(), RunError> {
        let prefix = format!("{},{:.4}", frame.index, frame.time);
        self.write_centreline(frame, &prefix)?;
        self.write_metrics(frame, &prefix)?;
        self.write_forces(frame, &prefix)?;
        self.write_contacts(frame, &prefix)?;
        self.write_internal(frame, &prefix)?;
        for file in [
            &mut self.centreline,
            &mut self.metrics,
            &mut self.forces,
            &mut self.contacts,
            &mut self.internal,
        ] {
            file.flush()?;
        }
        self.q.append(&frame.state.q)?;
        self.qdot.append(&frame.state.qdot)?;
        let thigmo = RECORDED_GROUPS.iter().position(|g| *g == hagfish_sim::rows::RowGroup::Thigmo);
        self.thigmo.append(thigmo.map_or(&[][..], |g| &frame.forces.values[g]))?;
        let loads: Vec<f64> = frame.internal.iter().flat_map(load_values).collect();
        self.internal_npy.append(&loads)
    }

    /// Writes `checkpoint.ron` (atomically) with the current file lengths.
    fn checkpoint(&mut self, checkpoint: &mut Checkpoint) -> Result<(), RunError> {
        checkpoint.files = self.files();
        checkpoint.write(&self.directory.join(CHECKPOINT_FILE))
    }
}

fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(String::new, |n| n.to_string_lossy().into_owned())
}
