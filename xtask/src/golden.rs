//! Golden files `data/regress/<scenario>.ron`: the blessed metrics of one scenario and the
//! platform they were blessed on.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::metrics::Value;

/// The platform of a build: the bitwise digest is compared only between equal platforms.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Platform {
    /// Target triple, e.g. `x86_64-unknown-linux-gnu`.
    pub target: String,
    /// `rustc --version` of the compiler.
    pub rustc: String,
}

impl Platform {
    /// The platform this program was built for.
    pub fn current() -> Self {
        Self { target: env!("XTASK_TARGET").to_owned(), rustc: env!("XTASK_RUSTC").to_owned() }
    }
}

/// The content of a golden file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Golden {
    /// Where it was blessed.
    pub platform: Platform,
    /// `(metric, value)` in table order (`metrics.rs`).
    pub metrics: Vec<(String, Value)>,
    /// `(metric, spread)`: how far each metric moved over the rounding-level perturbations of
    /// the bless (`tolerance.rs`); the tolerance is a multiple of it.
    pub spreads: Vec<(String, f64)>,
}

const HEADER: &str = "// Golden metrics of data/scenarios/{name}.ron for `cargo xtask regress`.\n\
// Written by `cargo xtask regress --bless`: the values as written and their spreads under\n\
// rounding-level perturbations of the time step; tolerances from them: xtask/src/tolerance.rs.\n";

impl Golden {
    /// The measured spread of metric `name` (0 for a metric the golden has no spread of).
    pub fn spread(&self, name: &str) -> f64 {
        self.spreads.iter().find(|(n, _)| n == name).map_or(0.0, |(_, s)| *s)
    }

    /// Reads the golden at `path`, or `None` if there is no such file.
    pub fn read(path: &Path) -> Result<Option<Self>, String> {
        match std::fs::read_to_string(path) {
            Ok(text) => {
                ron::from_str(&text).map(Some).map_err(|e| format!("{}: {e}", path.display()))
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(e) => Err(format!("{}: {e}", path.display())),
        }
    }

    /// Writes this golden for scenario `name` to `path`.
    pub fn write(&self, name: &str, path: &Path) -> Result<(), String> {
        let config = ron::ser::PrettyConfig::new().new_line("\n".to_owned());
        let body = ron::ser::to_string_pretty(self, config).map_err(|e| e.to_string())?;
        let text = format!("{}{body}\n", HEADER.replace("{name}", name));
        std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
    }
}
