//! Writes a run's outputs as it goes, flushing every frame, so a killed run keeps every
//! completed frame (`docs/outputs.md` describes the files and their columns).
//!
//! - `centreline.csv`: `frame,time_s,body,x_cm,y_cm,z_cm`, one row per body per frame.
//! - `metrics.csv`: one row per frame (see [`METRICS_HEADER`]).
//! - `forces.csv`: `frame,time_s,joint,axis,group,value_dyn_cm`, per DOF and recorded group.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use glam::DVec3;
use hagfish_control::KnotSpan;
use hagfish_knots::KnotReport;

use crate::error::SimError;
use crate::forces::{DofLabel, GroupForces, RECORDED_GROUPS};
use crate::report::StepReport;

/// Header of `forces.csv`: generalized constraint forces per joint, axis and group over the
/// step that ended at the frame (dyn·cm).
pub const FORCES_HEADER: &str = "frame,time_s,joint,axis,group,value_dyn_cm";

/// Header of `centreline.csv`.
pub const CENTRELINE_HEADER: &str = "frame,time_s,body,x_cm,y_cm,z_cm";

/// Header of `metrics.csv`. Contact and solver columns describe the step that ended at the
/// frame (measured at its start); penetration and limit columns are maxima over the steps since
/// the previous frame; knot columns describe the frame's centreline.
pub const METRICS_HEADER: &str = "frame,time_s,phase,self_contacts,wall_contacts,\
knot,knot_agreement,knot_first_body,knot_last_body,knot_position_cm,\
max_self_penetration_cm,max_self_penetration_rel,max_wall_penetration_cm,max_limit_excess_deg,\
contacts_start_cm,contacts_end_cm,first_contact_cm,last_contact_cm,\
solver_path,solver_status,solver_iterations,slack_rows,slack_max_cm_s";

/// Worst values over the steps between two frames.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct IntervalMaxima {
    /// Deepest self penetration (cm).
    pub self_penetration: f64,
    /// Deepest self penetration relative to the local radius.
    pub self_penetration_relative: f64,
    /// Deepest wall penetration (cm).
    pub wall_penetration: f64,
    /// Largest excess of a joint over a limit (rad).
    pub limit_excess: f64,
}

impl IntervalMaxima {
    /// Takes the maxima of `self` and the step's.
    pub fn include(&mut self, step: &StepReport, limit_excess: f64) {
        self.self_penetration = self.self_penetration.max(step.max_self_penetration);
        self.self_penetration_relative =
            self.self_penetration_relative.max(step.max_self_penetration_relative);
        self.wall_penetration = self.wall_penetration.max(step.max_wall_penetration);
        self.limit_excess = self.limit_excess.max(limit_excess);
    }

    /// The maxima of both.
    pub fn merge(&mut self, other: &IntervalMaxima) {
        self.self_penetration = self.self_penetration.max(other.self_penetration);
        self.self_penetration_relative =
            self.self_penetration_relative.max(other.self_penetration_relative);
        self.wall_penetration = self.wall_penetration.max(other.wall_penetration);
        self.limit_excess = self.limit_excess.max(other.limit_excess);
    }
}

/// Where a run's frames go: files ([`Recorder`]) or memory (tests).
pub trait FrameSink {
    /// Takes one frame.
    fn record(&mut self, frame: &Frame<'_>) -> Result<(), SimError>;
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
    /// Body centres (cm).
    pub centres: &'a [DVec3],
    /// The report of the step that ended at this frame (default for frame 0).
    pub step: &'a StepReport,
    /// Worst values since the previous frame.
    pub maxima: &'a IntervalMaxima,
    /// Knot analysis of the centreline, if it succeeded.
    pub knot: Option<&'a KnotReport>,
    /// The stretch of body the self contacts span (of the step that ended at the frame).
    pub span: Option<KnotSpan>,
    /// Labels of the DOFs (joint, axis).
    pub labels: &'a [DofLabel],
    /// Generalized constraint forces of the step that ended at the frame.
    pub forces: &'a GroupForces,
}

/// The open output files of a run.
#[derive(Debug)]
pub struct Recorder {
    centreline: (PathBuf, BufWriter<File>),
    metrics: (PathBuf, BufWriter<File>),
    forces: (PathBuf, BufWriter<File>),
}

impl Recorder {
    /// Creates `directory` (and parents) and the output files with their headers.
    pub fn create(directory: &Path) -> Result<Self, SimError> {
        std::fs::create_dir_all(directory)
            .map_err(|source| SimError::Output { path: directory.to_path_buf(), source })?;
        let mut recorder = Self {
            centreline: open(&directory.join("centreline.csv"))?,
            metrics: open(&directory.join("metrics.csv"))?,
            forces: open(&directory.join("forces.csv"))?,
        };
        write_line(&mut recorder.forces, format_args!("{FORCES_HEADER}"))?;
        write_line(&mut recorder.centreline, format_args!("{CENTRELINE_HEADER}"))?;
        write_line(&mut recorder.metrics, format_args!("{METRICS_HEADER}"))?;
        Ok(recorder)
    }
}

impl FrameSink for Recorder {
    /// Appends one frame to every file and flushes them.
    fn record(&mut self, frame: &Frame<'_>) -> Result<(), SimError> {
        for (body, c) in frame.centres.iter().enumerate() {
            write_line(
                &mut self.centreline,
                format_args!(
                    "{},{:.4},{body},{:.6},{:.6},{:.6}",
                    frame.index, frame.time, c.x, c.y, c.z
                ),
            )?;
        }
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
        let (s, m) = (frame.step, frame.maxima);
        let span = frame.span.map_or(",,,".to_string(), |k| {
            format!(
                "{:.3},{:.3},{:.3},{:.3}",
                k.start_cm, k.end_cm, k.first_contact_cm, k.last_contact_cm
            )
        });
        write_line(
            &mut self.metrics,
            format_args!(
                "{},{:.4},{},{},{},{knot},{agreement},{first},{last},{position},{:.6},{:.6},{:.6},{:.4},{span},{:?},{:?},{},{},{:.3e}",
                frame.index,
                frame.time,
                frame.phase,
                s.self_contacts,
                s.wall_contacts,
                m.self_penetration,
                m.self_penetration_relative,
                m.wall_penetration,
                m.limit_excess.to_degrees(),
                s.solve.path,
                s.solve.status,
                s.solve.iterations,
                s.solve.slack.count,
                s.solve.slack.max,
            ),
        )?;
        for (values, group) in frame.forces.values.iter().zip(RECORDED_GROUPS) {
            let name = GroupForces::group_name(group);
            for (label, value) in frame.labels.iter().zip(values) {
                write_line(
                    &mut self.forces,
                    format_args!(
                        "{},{:.4},{},{},{name},{value:.6e}",
                        frame.index, frame.time, label.joint, label.axis
                    ),
                )?;
            }
        }
        flush(&mut self.centreline)?;
        flush(&mut self.forces)?;
        flush(&mut self.metrics)
    }
}

fn open(path: &Path) -> Result<(PathBuf, BufWriter<File>), SimError> {
    File::create(path)
        .map(|f| (path.to_path_buf(), BufWriter::new(f)))
        .map_err(|source| SimError::Output { path: path.to_path_buf(), source })
}

fn write_line(
    file: &mut (PathBuf, BufWriter<File>),
    line: std::fmt::Arguments<'_>,
) -> Result<(), SimError> {
    writeln!(file.1, "{line}").map_err(|source| SimError::Output { path: file.0.clone(), source })
}

fn flush(file: &mut (PathBuf, BufWriter<File>)) -> Result<(), SimError> {
    file.1.flush().map_err(|source| SimError::Output { path: file.0.clone(), source })
}
