//! `metrics.csv`: the per-frame columns that the plots, the summary and the 3-D view use.

use std::path::Path;

use crate::csv::CsvFile;
use crate::error::ReportError;

/// The text columns read, in the order of [`Metrics::read`]'s destructuring.
const TEXT: [&str; 3] = ["phase", "knot", "solver_status"];
/// The number columns read (a value in every frame).
const NUMBER: [&str; 6] = [
    "time_s",
    "self_contacts",
    "wall_contacts",
    "max_self_penetration_rel",
    "max_wall_penetration_cm",
    "max_limit_excess_deg",
];
/// The number columns that may be empty in a frame.
const OPTIONAL: [&str; 6] = [
    "knot_agreement",
    "knot_position_cm",
    "contacts_start_cm",
    "contacts_end_cm",
    "first_contact_cm",
    "last_contact_cm",
];
/// Columns added after the first runs: all empty when a run directory lacks them.
const LATER: [&str; 5] = [
    "knot_core_start_cm",
    "knot_core_end_cm",
    "knot_core_start_L",
    "knot_core_mid_L",
    "knot_core_length_D",
];

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
        let file = CsvFile::open(path)?;
        let columns = |names: &[&str]| -> Result<Vec<usize>, ReportError> {
            names.iter().map(|name| file.column(name)).collect()
        };
        let (text, number, optional) = (columns(&TEXT)?, columns(&NUMBER)?, columns(&OPTIONAL)?);
        // Columns added later: empty for run directories written before them.
        let later: Vec<Option<usize>> = LATER.iter().map(|name| file.column(name).ok()).collect();
        let mut texts = [(); TEXT.len()].map(|()| Vec::new());
        let mut numbers = [(); NUMBER.len()].map(|()| Vec::new());
        let mut optionals = [(); OPTIONAL.len() + LATER.len()].map(|()| Vec::new());
        file.for_each_record(|record| {
            for (values, &c) in texts.iter_mut().zip(&text) {
                values.push(record.text(c).to_string());
            }
            for (values, &c) in numbers.iter_mut().zip(&number) {
                values.push(record.number(c)?);
            }
            let optional = optional.iter().map(|&c| Some(c)).chain(later.iter().copied());
            for (values, c) in optionals.iter_mut().zip(optional) {
                values.push(c.map(|c| record.optional(c)).transpose()?.flatten());
            }
            Ok(())
        })?;
        let [time, self_contacts, wall_contacts, self_penetration_rel, wall_penetration, limit] =
            numbers;
        if time.is_empty() {
            return Err(ReportError::Invalid { path: path.to_path_buf(), what: "no frame".into() });
        }
        let [phase, knot, solver_status] = texts;
        let [
            knot_agreement,
            knot_position,
            contacts_start,
            contacts_end,
            first_contact,
            last_contact,
            knot_core_start,
            knot_core_end,
            knot_core_start_l,
            knot_core_mid_l,
            knot_core_length_d,
        ] = optionals;
        Ok(Self {
            time,
            phase,
            knot,
            knot_agreement,
            solver_status,
            self_contacts,
            wall_contacts,
            knot_position,
            knot_core_start,
            knot_core_end,
            knot_core_start_l,
            knot_core_mid_l,
            knot_core_length_d,
            contacts_start,
            contacts_end,
            first_contact,
            last_contact,
            self_penetration_rel,
            wall_penetration,
            limit_excess_deg: limit,
        })
    }

    /// Number of frames.
    pub fn frames(&self) -> usize {
        self.time.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `metrics.csv` of the columns read here, without the later ones unless `later`.
    fn file(rows: &[&str], later: bool) -> crate::test_files::TestFile {
        let mut names: Vec<&str> = [&TEXT[..], &NUMBER, &OPTIONAL].concat();
        if later {
            names.extend(LATER);
        }
        let mut text = names.join(",") + "\n";
        for row in rows {
            text += row;
            text += "\n";
        }
        crate::test_files::write("metrics.csv", &text)
    }

    #[test]
    fn columns_by_name_with_empty_fields_as_none_and_later_columns_optional() {
        let old = file(&["slide,3_1,ok,0.5,2,1,0.01,0,0.2,0.9,,,,,"], false);
        let m = Metrics::read(&old).expect("reads");
        assert_eq!((m.phase[0].as_str(), m.knot[0].as_str()), ("slide", "3_1"));
        assert_eq!((m.time[0], m.self_contacts[0], m.limit_excess_deg[0]), (0.5, 2.0, 0.2));
        assert_eq!((m.knot_agreement[0], m.knot_position[0]), (Some(0.9), None));
        assert_eq!(m.knot_core_mid_l, [None], "a run directory written before the column");
        let new = file(&["tie,0_1,ok,0,0,0,0,0,0,,,,,,,1,2,0.1,0.2,3.5"], true);
        let m = Metrics::read(&new).expect("reads");
        assert_eq!((m.knot_core_start[0], m.knot_core_length_d[0]), (Some(1.0), Some(3.5)));
    }

    #[test]
    fn no_frame_or_a_bad_number_is_an_error_naming_the_file() {
        let empty = Metrics::read(&file(&[], true)).expect_err("no frame").to_string();
        assert!(empty.contains("metrics.csv: no frame"), "{empty}");
        let bad = file(&["tie,0_1,ok,0,x,0,0,0,0,,,,,,,,,,,"], true);
        let error = Metrics::read(&bad).expect_err("x").to_string();
        assert!(error.contains("metrics.csv:2:") && error.contains("\"x\""), "{error}");
    }
}
