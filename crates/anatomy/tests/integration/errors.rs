//! Malformed data files: each problem is a typed error whose message names the field and
//! gives `file:line:column`.

use std::path::Path;

use hagfish_anatomy::{AnatomyError, Biometrics, Origin};

const ES103: &str = include_str!("../../../../data/hagfish/es103.ron");
const PATH: &str = "bad.ron";

/// A malformed copy of ES103: `from` (which must occur exactly once) replaced by `to`.
struct Edit {
    text: String,
    /// Byte offset of the replacement in `text`.
    start: usize,
    to: &'static str,
}

impl Edit {
    fn new(from: &str, to: &'static str) -> Self {
        assert_eq!(ES103.matches(from).count(), 1, "{from:?} must occur once");
        let start = ES103.find(from).unwrap_or_default();
        Self { text: ES103.replacen(from, to, 1), start, to }
    }

    /// Parses the text, which must fail.
    fn error(&self) -> AnatomyError {
        match Biometrics::from_ron(self.text.as_bytes(), Path::new(PATH)) {
            Ok(_) => panic!("{:?} was accepted", self.to),
            Err(e) => e,
        }
    }

    /// 1-based line and column (in characters) of `needle`'s first occurrence from the
    /// start of the replacement on.
    fn position_of(&self, needle: &str) -> (usize, usize) {
        let Some(offset) = self.text[self.start..].find(needle) else {
            panic!("{needle:?} not found")
        };
        let before = &self.text[..self.start + offset];
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        (1 + before.matches('\n').count(), 1 + before[line_start..].chars().count())
    }
}

/// Asserts the error's origin is `PATH:line:column` and its message shows it and `words`.
fn assert_at(e: &AnatomyError, origin: &Origin, line: usize, column: usize, words: &[&str]) {
    let expected = Origin::Position { path: PATH.into(), line, column };
    assert_eq!(origin, &expected, "{e}");
    let message = e.to_string();
    assert!(message.starts_with(&format!("{PATH}:{line}:{column}: ")), "{message}");
    for w in words {
        assert!(message.contains(w), "{message:?} lacks {w:?}");
    }
}

/// Asserts an out-of-range error on `field` located at `value_text` within `to`.
fn assert_out_of_range(from: &str, to: &'static str, field: &str, value_text: &str) {
    let edit = Edit::new(from, to);
    let e = edit.error();
    let AnatomyError::OutOfRange { at, field: f, .. } = &e else { panic!("{e:?}") };
    assert_eq!(f.to_string(), field);
    let (line, column) = edit.position_of(value_text);
    assert_at(&e, at, line, column, &[field]);
}

#[test]
fn ron_syntax_error_has_line_and_column() {
    let edit = Edit::new("length_cm: 42.4,", "length_cm: 42.4");
    let e = edit.error();
    let AnatomyError::Parse { at, .. } = &e else { panic!("{e:?}") };
    let (line, column) = edit.position_of("mass_g");
    assert_at(&e, at, line, column, &["comma"]);
}

#[test]
fn missing_field_is_typed_and_named() {
    let edit = Edit::new("    mass_g: 80.0,\n", "");
    let e = edit.error();
    let AnatomyError::MissingField { at, field } = &e else { panic!("{e:?}") };
    assert_eq!(*field, "mass_g");
    let line = edit.text.lines().count();
    assert_at(&e, at, line, 1, &["missing field `mass_g`"]);
}

#[test]
fn unknown_field_is_typed_and_named() {
    let edit = Edit::new("mass_g: 80.0", "mass: 80.0");
    let e = edit.error();
    let AnatomyError::UnknownField { at, field, expected } = &e else { panic!("{e:?}") };
    assert_eq!(field, "mass");
    assert!(expected.contains(&"mass_g"));
    let (line, column) = edit.position_of("mass:");
    assert_at(&e, at, line, column, &["unknown field `mass`", "mass_g"]);
}

#[test]
fn negative_or_zero_mass_and_length_are_rejected() {
    assert_out_of_range("mass_g: 80.0", "mass_g: -80.0", "mass_g", "-80.0");
    assert_out_of_range("mass_g: 80.0", "mass_g: 0.0", "mass_g", "0.0");
    assert_out_of_range("length_cm: 42.4", "length_cm: -1.0", "length_cm", "-1.0");
}

#[test]
fn non_finite_values_are_rejected() {
    assert_out_of_range("length_cm: 42.4", "length_cm: inf", "length_cm", "inf");
    assert_out_of_range(
        "damping_dyn_cm_s_per_rad: 0.1",
        "damping_dyn_cm_s_per_rad: NaN",
        "damping_dyn_cm_s_per_rad",
        "NaN",
    );
}

#[test]
fn non_positive_circumference_is_rejected() {
    assert_out_of_range(
        "[5.6, 5.5, 5.6, 4.3]",
        "[5.6, 5.5, 0.0, 4.3]",
        "circumferences_cm[2]",
        "0.0, 4.3",
    );
    assert_out_of_range(
        "[5.6, 5.5, 5.6, 4.3]",
        "[-5.6, 5.5, 5.6, 4.3]",
        "circumferences_cm[0]",
        "-5.6",
    );
}

#[test]
fn limits_of_0_and_180_degrees_are_rejected() {
    assert_out_of_range(
        "[21.0, 75.0, 45.0, 51.0]",
        "[21.0, 0.0, 45.0, 51.0]",
        "bending_limits_deg[1]",
        "0.0, 45.0",
    );
    assert_out_of_range(
        "[21.0, 75.0, 45.0, 51.0]",
        "[21.0, 75.0, 45.0, 180.0]",
        "bending_limits_deg[3]",
        "180.0",
    );
    assert_out_of_range(
        "twist_limit_deg: 48.0",
        "twist_limit_deg: 180.0",
        "twist_limit_deg",
        "180.0",
    );
    assert_out_of_range("twist_limit_deg: 48.0", "twist_limit_deg: 0.0", "twist_limit_deg", "0.0");
}

#[test]
fn non_increasing_marks_are_rejected() {
    let edit = Edit::new("[0.2, 0.4, 0.6, 0.8]", "[0.2, 0.4, 0.4, 0.8]");
    let e = edit.error();
    let AnatomyError::NotIncreasing { at, field, value, previous } = &e else { panic!("{e:?}") };
    assert_eq!((field.to_string().as_str(), *value, *previous), ("mark_fractions[2]", 0.4, 0.4));
    let (line, column) = edit.position_of("0.4, 0.8");
    assert_at(&e, at, line, column, &["mark_fractions[2]"]);
}

#[test]
fn marks_outside_the_body_are_rejected() {
    assert_out_of_range(
        "[0.2, 0.4, 0.6, 0.8]",
        "[0.2, 0.4, 0.6, 1.0]",
        "mark_fractions[3]",
        "1.0]",
    );
}

#[test]
fn array_length_mismatch_is_rejected() {
    let edit = Edit::new("[5.6, 5.5, 5.6, 4.3]", "[5.6, 5.5, 5.6]");
    let e = edit.error();
    let AnatomyError::LengthMismatch { at, field, got: 3, expected: 4 } = &e else {
        panic!("{e:?}")
    };
    assert_eq!(field.to_string(), "circumferences_cm");
    let (line, column) = edit.position_of("[5.6, 5.5, 5.6]");
    assert_at(&e, at, line, column, &["circumferences_cm"]);
}

#[test]
fn too_few_bodies_and_bad_taper_are_rejected() {
    assert_out_of_range(" body_count: 100", " body_count: 1", "body_count", "1,");
    assert_out_of_range(
        "reference_body_count: 100",
        "reference_body_count: 0",
        "reference_body_count",
        "0,",
    );
    assert_out_of_range(
        "tail_taper: None",
        "tail_taper: Some(TailTaper(tip_radius_cm: -0.3))",
        "tail_taper.tip_radius_cm",
        "-0.3",
    );
}

#[test]
fn missing_file_names_the_path() {
    let e = Biometrics::load("no/such/file.ron").err();
    let Some(e @ AnatomyError::Io { .. }) = e else { panic!("{e:?}") };
    assert!(e.to_string().starts_with("no/such/file.ron: "), "{e}");
}

#[test]
fn invalid_utf8_has_a_position() {
    let bytes = b"Biometrics(\n  specimen: \"E\xff\",\n)";
    let e = Biometrics::from_ron(bytes, Path::new(PATH)).err();
    let Some(AnatomyError::NotUtf8 { at }) = e else { panic!("{e:?}") };
    assert_eq!(at, Origin::Position { path: PATH.into(), line: 2, column: 15 });
}

#[test]
fn values_built_in_code_are_validated_too() -> Result<(), AnatomyError> {
    let good =
        Biometrics::load(concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/hagfish/es103.ron"))?;
    let bad = Biometrics { mass_g: -1.0, ..good };
    let e = bad.to_model().err();
    let Some(e @ AnatomyError::OutOfRange { at: Origin::InMemory, .. }) = e else {
        panic!("{e:?}")
    };
    assert!(e.to_string().starts_with("biometrics: mass_g = -1"), "{e}");
    Ok(())
}
