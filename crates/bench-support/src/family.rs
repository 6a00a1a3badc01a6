//! The family of bodies and time steps the knot scenarios are judged on (issue #14), without
//! retuning: ES103 in both handednesses, length 35 and 50 cm (mass ∝ length), circumferences
//! ±15 %, stiffness ×0.1 and ×10, damping ×10, 50 and 300 bodies, the tail taper, h = 0.005
//! and 0.02 s, drag ×0.5 and ×2. Each member is ES103's biometrics file with text edits and
//! `hagfish run --set` overrides; `tests/integration/tie_family.rs` asserts on it and `cargo xtask
//! family` tabulates it.

/// One member of the family.
#[derive(Clone, Debug, PartialEq)]
pub struct Variant {
    /// A short name (a file stem).
    pub name: &'static str,
    /// Edits of ES103's biometrics file: each first text replaced by the second.
    pub edits: Vec<(&'static str, String)>,
    /// `--set PATH=VALUE` overrides of the scenario.
    pub sets: Vec<&'static str>,
    /// The handedness a trefoil is tied with (the sign of its core's writhe).
    pub right_handed: bool,
}

impl Variant {
    /// A right-handed member.
    fn new(
        name: &'static str,
        edits: Vec<(&'static str, String)>,
        sets: Vec<&'static str>,
    ) -> Self {
        Self { name, edits, sets, right_handed: true }
    }

    /// ES103's biometrics file `es103` with this member's edits, or the first edit whose text
    /// it does not contain.
    pub fn body(&self, es103: &str) -> Result<String, String> {
        edited(es103, &self.edits)
    }
}

/// `text` with each `(from, to)` of `edits` replaced in turn, or the first `from` it lacks.
pub fn edited(text: &str, edits: &[(&str, String)]) -> Result<String, String> {
    edits.iter().try_fold(text.to_owned(), |text, (from, to)| {
        if text.contains(from) {
            Ok(text.replace(from, to))
        } else {
            Err(format!("ES103's biometrics no longer contain `{from}`"))
        }
    })
}

/// The edits of ES103 to a body `length_cm` long, its mass in proportion.
pub fn length_edits(length_cm: f64) -> Vec<(&'static str, String)> {
    vec![
        ("length_cm: 42.4", format!("length_cm: {length_cm}")),
        ("mass_g: 80.0", format!("mass_g: {}", 80.0 * length_cm / 42.4)),
    ]
}

/// One edit of the biometrics: the field and value `from` (`name: value`) gets the value
/// `value`.
fn edit(from: &'static str, value: &str) -> Vec<(&'static str, String)> {
    let name = from.split(':').next().unwrap_or(from);
    vec![(from, format!("{name}: {value}"))]
}

/// The edits of ES103 to circumferences `k` times its own.
fn circumference_edits(k: f64) -> Vec<(&'static str, String)> {
    let scaled: Vec<String> =
        [5.6, 5.5, 5.6, 4.3].iter().map(|c| format!("{:.3}", c * k)).collect();
    vec![(
        "circumferences_cm: [5.6, 5.5, 5.6, 4.3]",
        format!("circumferences_cm: [{}]", scaled.join(", ")),
    )]
}

/// The edits of ES103 to bending and twist stiffness `k` times its own.
fn stiffness_edits(k: f64) -> Vec<(&'static str, String)> {
    vec![
        ("bending_stiffness_dyn_cm_per_rad: 1.0", format!("bending_stiffness_dyn_cm_per_rad: {k}")),
        (
            "twist_stiffness_dyn_cm_per_rad: 5.0",
            format!("twist_stiffness_dyn_cm_per_rad: {}", 5.0 * k),
        ),
    ]
}

/// The sixteen members, ES103 first.
pub fn family() -> Vec<Variant> {
    let body_count = |n: usize| vec![(" body_count: 100", format!(" body_count: {n}"))];
    vec![
        Variant::new("es103", vec![], vec![]),
        Variant {
            right_handed: false,
            ..Variant::new("es103_left", vec![], vec!["phases[0].Tie.knot=Trefoil(Left)"])
        },
        Variant::new("length_35", length_edits(35.0), vec![]),
        Variant::new("length_50", length_edits(50.0), vec![]),
        Variant::new("circumference_0.85", circumference_edits(0.85), vec![]),
        Variant::new("circumference_1.15", circumference_edits(1.15), vec![]),
        Variant::new("stiffness_0.1", stiffness_edits(0.1), vec![]),
        Variant::new("stiffness_10", stiffness_edits(10.0), vec![]),
        Variant::new("damping_10", edit("damping_dyn_cm_s_per_rad: 0.1", "1.0"), vec![]),
        Variant::new("bodies_50", body_count(50), vec![]),
        Variant::new("bodies_300", body_count(300), vec![]),
        Variant::new("taper", edit("tail_taper: None", "Some((tip_radius_cm: 0.3))"), vec![]),
        Variant::new("h_0.005", vec![], vec!["time_step_s=0.005"]),
        Variant::new("h_0.02", vec![], vec!["time_step_s=0.02"]),
        Variant::new("drag_0.5", vec![], vec!["drag.quadratic_g_per_cm3=0.25"]),
        Variant::new("drag_2", vec![], vec!["drag.quadratic_g_per_cm3=1.0"]),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_member_edits_the_shipped_biometrics() {
        let es103 = include_str!("../../../data/hagfish/es103.ron");
        for variant in family() {
            let body = variant.body(es103).unwrap_or_else(|e| panic!("{}: {e}", variant.name));
            assert_eq!(body == es103, variant.edits.is_empty(), "{}", variant.name);
        }
        let missing = edited(es103, &[("no such text", String::new())]);
        assert!(missing.is_err_and(|e| e.contains("no such text")));
    }
}
