//! `metrics.csv`: the per-frame columns that the plots, the summary and the 3-D view use.

use std::path::Path;

use crate::csv::{CsvFile, Record};
use crate::error::ReportError;

/// The columns of `metrics.csv` used here, one entry per frame. Empty fields (e.g. no knot
/// stretch, no contact) are `None`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Metrics {
    /// `time_s` (s).
    pub time: Vec<f64>,
    /// `phase`.
    pub phase: Vec<String>,
    /// `knot` (Rolfsen name or Alexander polynomial).
    pub knot: Vec<String>,
    /// `knot_agreement` (fraction of closure directions).
    pub knot_agreement: Vec<Option<f64>>,
    /// `solver_status`.
    pub solver_status: Vec<String>,
    /// `self_contacts`.
    pub self_contacts: Vec<f64>,
    /// `wall_contacts`.
    pub wall_contacts: Vec<f64>,
    /// `knot_position_cm`.
    pub knot_position: Vec<Option<f64>>,
    /// `knot_core_start_cm` (all `None` in a run directory written before the column).
    pub knot_core_start: Vec<Option<f64>>,
    /// `knot_core_end_cm` (likewise).
    pub knot_core_end: Vec<Option<f64>>,
    /// `knot_core_start_L`: the core's head-ward end as a fraction of the body length.
    pub knot_core_start_l: Vec<Option<f64>>,
    /// `knot_core_mid_L`: the core's midpoint as a fraction of the body length.
    pub knot_core_mid_l: Vec<Option<f64>>,
    /// `knot_core_length_D`: the core's length in local diameters.
    pub knot_core_length_d: Vec<Option<f64>>,
    /// `contacts_start_cm`.
    pub contacts_start: Vec<Option<f64>>,
    /// `contacts_end_cm`.
    pub contacts_end: Vec<Option<f64>>,
    /// `first_contact_cm`.
    pub first_contact: Vec<Option<f64>>,
    /// `last_contact_cm`.
    pub last_contact: Vec<Option<f64>>,
    /// `max_self_penetration_rel`.
    pub self_penetration_rel: Vec<f64>,
    /// `max_wall_penetration_cm`.
    pub wall_penetration: Vec<f64>,
    /// `max_limit_excess_deg`.
    pub limit_excess_deg: Vec<f64>,
}

impl Metrics {
    /// Reads `metrics.csv`; at least one frame is required.
    pub fn read(path: &Path) -> Result<Self, ReportError> {
        let file = CsvFile::read(path)?;
        let records: Vec<Record<'_>> = file.records().collect::<Result<_, _>>()?;
        if records.is_empty() {
            return Err(ReportError::Invalid { path: path.to_path_buf(), what: "no frame".into() });
        }
        let text = |name| -> Result<Vec<String>, ReportError> {
            let c = file.column(name)?;
            Ok(records.iter().map(|r| r.text(c).to_string()).collect())
        };
        let number = |name| -> Result<Vec<f64>, ReportError> {
            let c = file.column(name)?;
            records.iter().map(|r| r.number(c)).collect()
        };
        let optional = |name| -> Result<Vec<Option<f64>>, ReportError> {
            let c = file.column(name)?;
            records.iter().map(|r| r.optional(c)).collect()
        };
        // Columns added later: empty for run directories written before them.
        let later = |name| -> Result<Vec<Option<f64>>, ReportError> {
            match file.column(name) {
                Ok(c) => records.iter().map(|r| r.optional(c)).collect(),
                Err(_) => Ok(vec![None; records.len()]),
            }
        };
        Ok(Self {
            time: number("time_s")?,
            phase: text("phase")?,
            knot: text("knot")?,
            knot_agreement: optional("knot_agreement")?,
            solver_status: text("solver_status")?,
            self_contacts: number("self_contacts")?,
            wall_contacts: number("wall_contacts")?,
            knot_position: optional("knot_position_cm")?,
            knot_core_start: later("knot_core_start_cm")?,
            knot_core_end: later("knot_core_end_cm")?,
            knot_core_start_l: later("knot_core_start_L")?,
            knot_core_mid_l: later("knot_core_mid_L")?,
            knot_core_length_d: later("knot_core_length_D")?,
            contacts_start: optional("contacts_start_cm")?,
            contacts_end: optional("contacts_end_cm")?,
            first_contact: optional("first_contact_cm")?,
            last_contact: optional("last_contact_cm")?,
            self_penetration_rel: number("max_self_penetration_rel")?,
            wall_penetration: number("max_wall_penetration_cm")?,
            limit_excess_deg: number("max_limit_excess_deg")?,
        })
    }

    /// Number of frames.
    pub fn frames(&self) -> usize {
        self.time.len()
    }
}
