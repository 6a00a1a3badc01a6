//! The body radii of a run: from the body file that the run directory's `scenario.ron`
//! names, else a constant.

use std::path::Path;

use hagfish_scenario::LoadedScenario;

/// The radius used when the run directory does not give the body (cm): about the mean
/// radius of ES103.
pub const DEFAULT_RADIUS_CM: f64 = 0.85;

/// One radius per body (cm) and where they came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Radii {
    /// Radius of each body (cm), head first.
    pub values: Vec<f64>,
    /// A sentence for the report: the body file, or why the constant was used.
    pub source: String,
}

impl Radii {
    /// The radii of `bodies` bodies: derived from the body file named by `scenario` (read as
    /// a scenario file, its body path relative to it, as `hagfish run` reads it) if that file
    /// exists, loads and has as many bodies; else [`DEFAULT_RADIUS_CM`] for every body.
    pub fn for_run(scenario: &Path, bodies: usize) -> Self {
        let constant = |why: String| Self {
            values: vec![DEFAULT_RADIUS_CM; bodies],
            source: format!("constant {DEFAULT_RADIUS_CM} cm ({why})"),
        };
        if !scenario.exists() {
            return constant(format!("no {}", scenario.display()));
        }
        let table = LoadedScenario::load(scenario)
            .map_err(|e| e.to_string())
            .and_then(|s| s.body.body_table().map_err(|e| e.to_string()));
        match table {
            Ok(t) if t.rows.len() == bodies => Self {
                values: t.rows.iter().map(|r| r.radius_cm).collect(),
                source: format!("the body file named by {}", scenario.display()),
            },
            Ok(t) => {
                constant(format!("the body file has {} bodies, the run {bodies}", t.rows.len()))
            }
            Err(e) => constant(e),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_form_scenario_gives_es103_radii_and_a_missing_one_the_constant() {
        let form = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/scenarios/form.ron");
        let radii = Radii::for_run(&form, 100);
        assert_eq!(radii.values.len(), 100);
        assert!(radii.source.contains("body file"), "{}", radii.source);
        assert!(radii.values.iter().all(|r| *r > 0.1 && *r < 2.0), "{:?}", radii.values);
        assert!(radii.values[0] != radii.values[99]);

        let wrong_count = Radii::for_run(&form, 7);
        assert_eq!(wrong_count.values, vec![DEFAULT_RADIUS_CM; 7]);
        let missing = Radii::for_run(Path::new("/nonexistent/scenario.ron"), 3);
        assert_eq!(missing.values, vec![DEFAULT_RADIUS_CM; 3]);
        assert!(missing.source.starts_with("constant"));
    }
}
