//! The VALUE of a `--set PATH=VALUE` override: RON, the notation of the scenario files, read by
//! `ron` into the serde data model the scenario is overridden in (`overrides.rs`).
//!
//! What a value may be, as in RON: `None`, `true`, `false`, a number (`2`, `-0.5`, `1e-3`;
//! finite), a quoted string (`"../hagfish/es103.ron"`), `Some(VALUE)` (serde writes `Some(x)`
//! as `x`), an enum variant without data (`SparseMaximal`), a variant with data (`Trefoil(Left)`,
//! `Tie((knot: FigureEight, at: 0.31))`, read as `{"Variant": VALUE}`), a tuple `(0.0, 2.0)`
//! (also the fields of a struct in their order), a struct by field names
//! (`(linear_dyn_s_per_cm3: 0.0, quadratic_g_per_cm3: 1.0)`) or a list `[VALUE, …]`. Trailing
//! commas are allowed.
//!
//! The text is read twice, both times by `ron`:
//! - a check, which refuses what RON accepts but a value must not be: a number that is not
//!   finite (serde would write it as `None`), `Some(Some(…))` (the scenario has no option of an
//!   option, and serde's data model would silently drop one `Some`) and a field given twice;
//! - the reading proper, into serde's buffered content, the one form in which `ron` keeps the
//!   names of enum variants (`Trefoil(Left)` → `{"Trefoil": "Left"}`).
//!
//! Both are bounded by `RECURSION_LIMIT` levels of nesting, so a deeply nested value is an error,
//! not a stack overflow. An error names the column (from 1) where the text stops fitting.

use std::collections::BTreeSet;
use std::fmt;

use serde::Deserialize;
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::Value;

/// `ron`'s recursion limit for a value: its levels of nesting, a list or a variant counting
/// twice, so at least 32 levels of brackets; the deepest value of a scenario has 6.
const RECURSION_LIMIT: usize = 64;

/// Parses an override's VALUE (see the module documentation).
///
/// # Errors
/// What is wrong and the column (from 1, in characters) where `ron` found it.
pub fn parse_override_value(text: &str) -> Result<Value, String> {
    let options = ron::Options::default().with_recursion_limit(RECURSION_LIMIT);
    options.from_str::<Checked>(text).map_err(|e| positioned(&e))?;
    let Buffered::Tree(tree) = options.from_str::<Buffered>(text).map_err(|e| positioned(&e))?;
    Ok(tree)
}

/// `ron`'s error with its place in the value: a column, and a line if the value has several.
fn positioned(error: &ron::error::SpannedError) -> String {
    let ron::error::Position { line, col } = error.span.start;
    let what = match &error.code {
        ron::Error::ExceededRecursionLimit => {
            format!("expected at most {RECURSION_LIMIT} levels of nesting (lists count twice)")
        }
        code => code.to_string(),
    };
    match line {
        1 => format!("{what} at column {col}"),
        _ => format!("{what} at line {line}, column {col}"),
    }
}

/// The value as a tree in serde's data model. Untagged, so that serde buffers the value in its
/// content type first: for that type `ron` reads a variant with its name (as a map of one
/// entry, the form serde_json gives an enum), where a plain tree would lose the name.
#[derive(Deserialize)]
#[serde(untagged)]
enum Buffered {
    /// The whole value.
    Tree(Value),
}

/// A value that passed the check (see the module documentation); it keeps nothing.
struct Checked;

impl<'de> Deserialize<'de> for Checked {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        Check { in_some: false }.deserialize(deserializer)
    }
}

/// The check of one value; `in_some` when it is the content of a `Some`.
#[derive(Clone, Copy)]
struct Check {
    in_some: bool,
}

impl<'de> DeserializeSeed<'de> for Check {
    type Value = Checked;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Checked, D::Error> {
        deserializer.deserialize_any(self)
    }
}

impl<'de> Visitor<'de> for Check {
    type Value = Checked;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a value as in the scenario files")
    }

    fn visit_bool<E>(self, _: bool) -> Result<Checked, E> {
        Ok(Checked)
    }

    fn visit_i64<E>(self, _: i64) -> Result<Checked, E> {
        Ok(Checked)
    }

    fn visit_u64<E>(self, _: u64) -> Result<Checked, E> {
        Ok(Checked)
    }

    fn visit_i128<E>(self, _: i128) -> Result<Checked, E> {
        Ok(Checked)
    }

    fn visit_u128<E>(self, _: u128) -> Result<Checked, E> {
        Ok(Checked)
    }

    fn visit_f64<E: de::Error>(self, number: f64) -> Result<Checked, E> {
        match number.is_finite() {
            true => Ok(Checked),
            false => Err(E::custom(format!("expected a finite number, not `{number}`"))),
        }
    }

    fn visit_char<E>(self, _: char) -> Result<Checked, E> {
        Ok(Checked)
    }

    fn visit_str<E>(self, _: &str) -> Result<Checked, E> {
        Ok(Checked)
    }

    fn visit_bytes<E>(self, _: &[u8]) -> Result<Checked, E> {
        Ok(Checked)
    }

    fn visit_none<E>(self) -> Result<Checked, E> {
        Ok(Checked)
    }

    fn visit_unit<E>(self) -> Result<Checked, E> {
        Ok(Checked)
    }

    fn visit_some<D: Deserializer<'de>>(self, inner: D) -> Result<Checked, D::Error> {
        if self.in_some {
            let message = "expected one `Some` around a value, not `Some(Some(…))`";
            return Err(de::Error::custom(message));
        }
        Check { in_some: true }.deserialize(inner)
    }

    fn visit_newtype_struct<D: Deserializer<'de>>(self, inner: D) -> Result<Checked, D::Error> {
        Check { in_some: false }.deserialize(inner)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut items: A) -> Result<Checked, A::Error> {
        while items.next_element_seed(Check { in_some: false })?.is_some() {}
        Ok(Checked)
    }

    fn visit_map<A: MapAccess<'de>>(self, mut fields: A) -> Result<Checked, A::Error> {
        let mut names = BTreeSet::new();
        while let Some(name) = fields.next_key::<Value>()? {
            let name = match name {
                Value::String(name) => name,
                other => other.to_string(),
            };
            if !names.insert(name.clone()) {
                return Err(de::Error::custom(format!("expected the field `{name}` only once")));
            }
            fields.next_value_seed(Check { in_some: false })?;
        }
        Ok(Checked)
    }
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::*;

    fn parse(text: &str) -> Value {
        parse_override_value(text).unwrap_or_else(|e| panic!("{text}: {e}"))
    }

    #[test]
    fn scalars_and_identifiers() {
        assert_eq!(parse("2"), json!(2));
        assert_eq!(parse(" -0.5 "), json!(-0.5));
        assert_eq!(parse("1e-3"), json!(1e-3));
        assert_eq!(parse("0.1"), json!(0.1), "an f64 exactly as Rust parses it");
        assert_eq!(parse("None"), Value::Null);
        assert_eq!(parse("true"), json!(true));
        assert_eq!(parse("SparseMaximal"), json!("SparseMaximal"));
        assert_eq!(parse(r#""a \"b\" \\c""#), json!(r#"a "b" \c"#));
    }

    #[test]
    fn the_ron_of_the_scenario_files() {
        assert_eq!(parse("Some(0.35)"), json!(0.35));
        assert_eq!(parse("Trefoil(Left)"), json!({"Trefoil": "Left"}));
        assert_eq!(parse("(0.0, 2.0)"), json!([0.0, 2.0]));
        assert_eq!(parse("(1.0)"), json!([1.0]));
        assert_eq!(
            parse("Some((linear_dyn_s_per_cm3: 0.0, quadratic_g_per_cm3: 1.0,))"),
            json!({"linear_dyn_s_per_cm3": 0.0, "quadratic_g_per_cm3": 1.0})
        );
        assert_eq!(
            parse("Tie((knot: Trefoil(Right), at: 0.31, min_tail_d: Some(18.5)))"),
            json!({"Tie": {"knot": {"Trefoil": "Right"}, "at": 0.31, "min_tail_d": 18.5}})
        );
        assert_eq!(parse("((1, 2), (3, 4))"), json!([[1, 2], [3, 4]]));
        assert_eq!(parse("[Hold(1.0), Hold(2.0),]"), json!([{"Hold": 1.0}, {"Hold": 2.0}]));
        assert_eq!(parse("Pair(1, 2)"), json!({"Pair": [1, 2]}));
        assert_eq!(parse("[]"), json!([]));
        assert_eq!(parse("[Some(1), None]"), json!([1, null]), "options inside an option's list");
    }

    #[test]
    fn errors_name_the_column() {
        let error = |text: &str| parse_override_value(text).expect_err(text);
        assert_eq!(error("(a: 1, b 2)"), "Expected colon at column 9");
        assert_eq!(error("(1, 2"), "Expected comma at column 5");
        assert!(error("Some(1, 2)").ends_with("at column 8"), "{}", error("Some(1, 2)"));
        assert_eq!(error("(a: 1, a: 2)"), "expected the field `a` only once at column 8");
        assert!(error("\"open").ends_with("at column 1"));
        assert!(error("1 2").contains("trailing characters at column 2"));
        assert_eq!(error("-inf"), "expected a finite number, not `-inf` at column 1");
        assert!(error("NaN").contains("a finite number, not `NaN`"));
        assert!(error("(a: 1,\n b 2)").ends_with("at line 2, column 3"));
    }

    #[test]
    fn an_option_of_an_option_is_refused() {
        let error = parse_override_value("Some(Some(0.01))").expect_err("Some(Some(…))");
        assert!(error.contains("not `Some(Some(…))` at column"), "{error}");
        assert!(parse_override_value("Some([Some(1)])").is_ok(), "a list of options in Some");
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_stack_overflow() {
        for open in ["[", "(", "Trefoil(", "(a: "] {
            let text = open.repeat(15_000);
            let error = parse_override_value(&text).expect_err("15 000 levels");
            assert!(error.contains("levels of nesting"), "{open}: {error}");
        }
        let nested = |depth: usize| format!("{}1{}", "[".repeat(depth), "]".repeat(depth));
        assert!(parse_override_value(&nested(RECURSION_LIMIT / 2 - 1)).is_ok());
        let error = parse_override_value(&nested(RECURSION_LIMIT)).expect_err("too deep");
        assert_eq!(error, "expected at most 64 levels of nesting (lists count twice) at column 33");
    }
}
