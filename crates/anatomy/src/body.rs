//! A body file of either kind: a hagfish's biometrics or a uniform rod. Scenarios, `--body`
//! and `hagfish body` take both; the kind is the name the file's value starts with
//! (`Biometrics(…)` or `Rod(…)`).

use std::path::Path;

use hagfish_tree::Model;

use crate::biometrics::Biometrics;
use crate::error::AnatomyError;
use crate::load::DataFile;
use crate::rod::Rod;
use crate::table::BodyTable;

/// The body a scenario simulates.
#[derive(Clone, Debug, PartialEq)]
pub enum Body {
    /// A hagfish from its measured biometrics.
    Hagfish(Biometrics),
    /// A uniform elastic rod.
    Rod(Rod),
}

impl Body {
    /// Reads, parses and validates the body file at `path`; every error carries
    /// `file:line:column` (see [`Body::from_ron`]).
    pub fn load(path: impl AsRef<Path>) -> Result<Self, AnatomyError> {
        let path = path.as_ref();
        Self::from_ron(&crate::load::read_data_file(path)?, path)
    }

    /// Parses RON `bytes` as a [`Rod`] when the value is named `Rod(…)`, as [`Biometrics`]
    /// otherwise, and validates it; `path` names the source in messages.
    pub fn from_ron(bytes: &[u8], path: &Path) -> Result<Self, AnatomyError> {
        let text = String::from_utf8_lossy(bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes));
        if value_name(&text) == Some("Rod") {
            let file = DataFile::<Rod>::parse(bytes, path)?;
            file.value.validate_with(&|field| file.locate(field))?;
            Ok(Body::Rod(file.value))
        } else {
            Biometrics::from_ron(bytes, path).map(Body::Hagfish)
        }
    }

    /// The specimen label or the rod's name.
    pub fn name(&self) -> &str {
        match self {
            Body::Hagfish(b) => &b.specimen,
            Body::Rod(r) => &r.name,
        }
    }

    /// What kind of body: "hagfish" or "rod".
    pub fn kind(&self) -> &'static str {
        match self {
            Body::Hagfish(_) => "hagfish",
            Body::Rod(_) => "rod",
        }
    }

    /// Length L (cm).
    pub fn length_cm(&self) -> f64 {
        match self {
            Body::Hagfish(b) => b.length_cm,
            Body::Rod(r) => r.length_cm,
        }
    }

    /// Total mass (g).
    pub fn mass_g(&self) -> f64 {
        match self {
            Body::Hagfish(b) => b.mass_g,
            Body::Rod(r) => r.mass_g(),
        }
    }

    /// Number of rigid bodies N.
    pub fn body_count(&self) -> usize {
        match self {
            Body::Hagfish(b) => b.body_count,
            Body::Rod(r) => r.body_count,
        }
    }

    /// The derived per-body table.
    pub fn body_table(&self) -> Result<BodyTable, AnatomyError> {
        match self {
            Body::Hagfish(b) => b.body_table(),
            Body::Rod(r) => r.body_table(),
        }
    }

    /// The kinematic-tree model.
    pub fn to_model(&self) -> Result<Model, AnatomyError> {
        match self {
            Body::Hagfish(b) => b.to_model(),
            Body::Rod(r) => r.to_model(),
        }
    }
}

/// The name a RON value starts with (`Rod` in `// comment\nRod(length_cm: …)`), after
/// whitespace, comments and `#![enable(…)]` attributes; `None` for an unnamed value.
fn value_name(text: &str) -> Option<&str> {
    let mut rest = text.trim_start_matches('\u{feff}');
    loop {
        rest = rest.trim_start();
        if let Some(line) = rest.strip_prefix("//") {
            rest = line.split_once('\n').map_or("", |(_, after)| after);
        } else if let Some(block) = rest.strip_prefix("/*") {
            rest = block.split_once("*/").map_or("", |(_, after)| after);
        } else if rest.starts_with("#!") {
            rest = rest.split_once(']').map_or("", |(_, after)| after);
        } else {
            break;
        }
    }
    let end = rest.find(|c: char| !(c.is_alphanumeric() || c == '_')).unwrap_or(rest.len());
    (end > 0).then(|| &rest[..end])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_value_name_skips_comments_and_attributes() {
        assert_eq!(value_name("// a\n/* b */ #![enable(implicit_some)]\nRod(x: 1)"), Some("Rod"));
        assert_eq!(value_name("Biometrics(specimen: \"x\")"), Some("Biometrics"));
        assert_eq!(value_name("(length_cm: 1)"), None);
        assert_eq!(value_name("// only a comment"), None);
    }

    #[test]
    fn a_rod_file_loads_as_a_rod_and_a_biometrics_file_as_a_hagfish() {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data");
        let rod = Body::load(format!("{root}/rods/thin.ron")).expect("thin rod");
        assert_eq!(rod.kind(), "rod");
        let fish = Body::load(format!("{root}/hagfish/es103.ron")).expect("ES103");
        assert_eq!(fish.kind(), "hagfish");
        assert_eq!(fish.body_count(), 100);
    }

    #[test]
    fn a_bad_rod_value_is_placed_at_its_line_and_column() {
        let text = "Rod(\n  name: \"r\",\n  length_cm: 10.0,\n  radius_cm: 0.05,\n  body_count: 100,\n  density_g_per_cm3: 1.0,\n  bending_stiffness_dyn_cm2: -1.0,\n  twist_stiffness_dyn_cm2: 1.0,\n)";
        let error = Body::from_ron(text.as_bytes(), Path::new("rod.ron")).expect_err("B < 0");
        let message = error.to_string();
        assert!(message.starts_with("rod.ron:7:30:"), "{message}");
        assert!(message.contains("bending_stiffness_dyn_cm2"), "{message}");
    }
}
