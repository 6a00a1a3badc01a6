//! Overrides of scenario values for studies: `hagfish run SCENARIO --set PATH=VALUE` (and the
//! same from a library caller), applied to the scenario as read and before any check, so every
//! check applies to the overridden values.
//!
//! A PATH names a field with the dotted names that `hagfish params` lists:
//! - a top-level field: `time_step_s`, `duration_s`, `record_every_s`, `backend`, `body`,
//!   `drag`, `drag.quadratic_g_per_cm3`;
//! - a field of every phase of one kind, as `params` lists it: `Thigmotaxis.parameters.
//!   tail_pull_dyn`, `Thigmotaxis.until.seconds`, `Form.gains.kp_dyn_per_cm`;
//! - a field of one phase, by its index from 0: `phases[2].Thigmotaxis.parameters.head.v_a`.
//!
//! A VALUE is written as in the scenario files (`override_value.rs` reads it by `ron`): a number,
//! `true`/`false`, `None`, `Some(VALUE)`, a quoted string, an enum variant (`SparseMaximal`,
//! `Trefoil(Left)`), a tuple `(0.0, 2.0)`, a struct `(linear_dyn_s_per_cm3: 0.0,
//! quadratic_g_per_cm3: 1.0)` or a list `[…]`.
//!
//! Overrides work on the scenario's serde data model: the scenario is turned into a tree of
//! values, each override replaces one or more of its leaves (a path that names nothing is an
//! error listing the fields there), and the tree is turned back into a `Scenario`, so a value
//! of the wrong type is refused with the field's expected type.

use serde_json::{Map, Value};

use crate::error::{ECHO_HEAD, ECHO_TAIL, ScenarioError, echo};
use crate::override_value::parse_override_value;
use crate::scenario::Scenario;

/// The kinds of phase a kind-wide path may start with (`params` lists their fields so).
const PHASE_KINDS: [&str; 4] = ["Form", "Hold", "Thigmotaxis", "Tie"];

/// One `PATH=VALUE` override, as given.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Override {
    /// The dotted path.
    pub path: String,
    /// The value's text.
    pub value: String,
}

impl Override {
    /// Parses `PATH=VALUE` (the first `=` separates them; spaces around either are trimmed).
    ///
    /// # Errors
    /// [`ScenarioError::Override`] if there is no `=` or the path or the value is empty.
    pub fn parse(text: &str) -> Result<Self, ScenarioError> {
        let invalid = |reason: &str| ScenarioError::Override {
            given: text.to_owned(),
            reason: reason.to_owned(),
        };
        let (path, value) = text.split_once('=').ok_or_else(|| invalid("expected PATH=VALUE"))?;
        let (path, value) = (path.trim(), value.trim());
        if path.is_empty() || value.is_empty() {
            return Err(invalid("expected PATH=VALUE with a path and a value"));
        }
        Ok(Self { path: path.to_owned(), value: value.to_owned() })
    }

    /// `PATH=VALUE`, as given on the command line.
    pub fn text(&self) -> String {
        format!("{}={}", self.path, self.value)
    }

    /// The error of this override for `reason`, in which a long value (as given, or the
    /// string inside its quotes, as serde quotes it) is [`echo`]ed cut.
    fn error(&self, reason: impl Into<String>) -> ScenarioError {
        let mut reason = reason.into();
        let value = self.value.as_str();
        let inner = value.strip_prefix('"').and_then(|v| v.strip_suffix('"')).unwrap_or(value);
        for text in [value, inner] {
            if text.chars().count() > ECHO_HEAD + ECHO_TAIL {
                reason = reason.replace(text, &echo(text));
            }
        }
        ScenarioError::Override { given: self.text(), reason }
    }
}

/// `scenario` with `overrides` applied in order.
///
/// # Errors
/// [`ScenarioError::Override`] naming the override: a path that names no field, a value that does
/// not parse, or one of the wrong type for its field.
pub fn apply_overrides(
    scenario: &Scenario,
    overrides: &[Override],
) -> Result<Scenario, ScenarioError> {
    let mut tree = serde_json::to_value(scenario).map_err(|e| ScenarioError::Override {
        given: String::new(),
        reason: format!("the scenario has no data model: {e}"),
    })?;
    for given in overrides {
        let value = parse_override_value(&given.value)
            .map_err(|reason| given.error(format!("the value: {reason}")))?;
        let segments: Vec<&str> = given.path.split('.').collect();
        let targets = match segments.first() {
            Some(kind) if PHASE_KINDS.contains(kind) => phases_of_kind(&mut tree, kind),
            _ => vec![&mut tree],
        };
        if targets.is_empty() {
            return Err(given.error(format!("the scenario has no {} phase", segments[0])));
        }
        let leaf = match segments.first() {
            Some(kind) if PHASE_KINDS.contains(kind) => &segments[1..],
            _ => &segments[..],
        };
        let mut absent = None;
        for target in targets {
            absent = set(target, leaf, value.clone()).map_err(|reason| given.error(reason))?;
        }
        let overridden = serde_json::from_value::<Scenario>(tree.clone()).map_err(|e| {
            match &absent {
                // The leaf was added to the tree and names no field after all.
                Some(unknown) if e.to_string().starts_with("unknown field") => {
                    given.error(unknown.clone())
                }
                _ => given.error(format!(
                    "wrong value for {}: {}",
                    given.path,
                    explain(&e, &given.value)
                )),
            }
        })?;
        if let Some(unknown) = absent
            && !value.is_null()
            && !holds_a_value_at(&overridden, &segments)
        {
            // Read without complaint but not kept: no field of that name.
            return Err(given.error(unknown));
        }
        if is_list(&given.value) {
            refuse_list_for_struct(&overridden, &segments).map_err(|reason| given.error(reason))?;
        }
    }
    serde_json::from_value(tree).map_err(|e| ScenarioError::Override {
        given: overrides.iter().map(Override::text).collect::<Vec<_>>().join(" "),
        reason: e.to_string(),
    })
}

/// serde's reason for refusing `value`, with what to write instead where serde's words name
/// only its data model: a variant that holds a value given bare (`Trefoil` for
/// `Trefoil(Right)`).
fn explain(error: &serde_json::Error, value: &str) -> String {
    let reason = error.to_string();
    if reason.starts_with("invalid type: unit variant, expected") {
        format!("`{value}` holds a value: write it as `{value}(…)` (serde: {reason})")
    } else {
        reason
    }
}

/// Whether an override's VALUE is a list `[…]` (inside any `Some(…)`): serde reads a list into
/// a struct's fields in order, as it does a tuple, but a list names a sequence of like
/// values, so one given where a struct is expected is a mistake to refuse.
fn is_list(value: &str) -> bool {
    let mut rest = value.trim_start();
    while let Some(inner) = rest.strip_prefix("Some").map(str::trim_start) {
        match inner.strip_prefix('(') {
            Some(inner) => rest = inner.trim_start(),
            None => break,
        }
    }
    rest.starts_with('[')
}

/// Refuses an override at `segments` whose field in `overridden` is a struct (serde's map):
/// it was given as a list ([`is_list`]).
fn refuse_list_for_struct(overridden: &Scenario, segments: &[&str]) -> Result<(), String> {
    let mut back = serde_json::to_value(overridden).map_err(|e| e.to_string())?;
    let (targets, leaf) = match segments.first() {
        Some(kind) if PHASE_KINDS.contains(kind) => {
            (phases_of_kind(&mut back, kind), &segments[1..])
        }
        _ => (vec![&mut back], segments),
    };
    for target in targets {
        if let Some(Value::Object(fields)) = get(target, leaf) {
            let names: Vec<&str> = fields.keys().map(String::as_str).collect();
            return Err(format!(
                "`{}` is a struct with the fields {}: a list `[…]` names none of them; write \
                 `({}: …)`",
                segments.join("."),
                names.join(", "),
                names.join(": …, ")
            ));
        }
    }
    Ok(())
}

/// Whether `overridden`, written back as a tree, has a value at `segments` (kind-wide or from
/// the top, as an override's path): an added field that the scenario kept.
fn holds_a_value_at(overridden: &Scenario, segments: &[&str]) -> bool {
    let Ok(mut back) = serde_json::to_value(overridden) else { return false };
    let (targets, leaf) = match segments.first() {
        Some(kind) if PHASE_KINDS.contains(kind) => {
            (phases_of_kind(&mut back, kind), &segments[1..])
        }
        _ => (vec![&mut back], segments),
    };
    targets.into_iter().any(|target| get(target, leaf).is_some())
}

/// The value at `path` (as [`set`] reads it) under `node`, if there is one.
fn get<'a>(node: &'a Value, path: &[&str]) -> Option<&'a Value> {
    let Some((first, rest)) = path.split_first() else {
        return Some(node);
    };
    let (name, index) = split_index(first).ok()?;
    let child = node.get(name)?;
    let child = match index {
        None => child,
        Some(i) => child.get(i)?,
    };
    get(child, rest)
}

/// The bodies of every phase `{kind: …}` of `tree`'s `phases`.
fn phases_of_kind<'a>(tree: &'a mut Value, kind: &str) -> Vec<&'a mut Value> {
    match tree.get_mut("phases") {
        Some(Value::Array(phases)) => phases.iter_mut().filter_map(|p| p.get_mut(kind)).collect(),
        _ => Vec::new(),
    }
}

/// Sets the leaf at `path` (field names, each optionally with `[index]`) under `node`. A leaf
/// field absent from the tree is added: an optional field left out of the scenario's text
/// while `None` (`Thigmotaxis.parameters.replay`); the returned message is the one to give if
/// the scenario then has no such field after all (a misspelt name).
fn set(node: &mut Value, path: &[&str], value: Value) -> Result<Option<String>, String> {
    let Some((first, rest)) = path.split_first() else {
        *node = value;
        return Ok(None);
    };
    let (name, index) = split_index(first)?;
    let Value::Object(fields) = node else {
        return Err(format!("`{name}`: the value above it has no fields (it is {node})"));
    };
    let known = unknown_field(name, fields);
    if rest.is_empty() && index.is_none() && !fields.contains_key(name) {
        fields.insert(name.to_owned(), value);
        return Ok(Some(known));
    }
    let child = fields.get_mut(name).ok_or(known)?;
    let child = match index {
        None => child,
        Some(i) => match child {
            Value::Array(items) => {
                let count = items.len();
                items
                    .get_mut(i)
                    .ok_or_else(|| format!("`{name}` has {count} elements, no [{i}]"))?
            }
            _ => return Err(format!("`{name}` is not a list: no [{i}]")),
        },
    };
    if child.is_null() && !rest.is_empty() {
        return Err(format!("`{name}` is None: set it to Some(…) before its fields"));
    }
    // A phase or step variant wraps its fields: `phases[1].Thigmotaxis.until` names them.
    set(child, rest, value)
}

/// `name[i]` → (`name`, Some(i)); `name` → (`name`, None).
fn split_index(segment: &str) -> Result<(&str, Option<usize>), String> {
    match segment.split_once('[') {
        None => Ok((segment, None)),
        Some((name, rest)) => {
            let index = rest
                .strip_suffix(']')
                .and_then(|i| i.parse().ok())
                .ok_or_else(|| format!("`{segment}`: expected NAME[INDEX]"))?;
            Ok((name, Some(index)))
        }
    }
}

/// The message for a path segment `name` that is not among `fields`.
fn unknown_field(name: &str, fields: &Map<String, Value>) -> String {
    let known: Vec<&str> = fields.keys().map(String::as_str).collect();
    format!("no field `{name}` here; the fields are {}", known.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scenario() -> Scenario {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/scenarios/thesis_scripted.ron");
        crate::LoadedScenario::load(path).expect("thesis_scripted.ron").scenario
    }

    fn set_one(text: &str) -> Result<Scenario, ScenarioError> {
        apply_overrides(&scenario(), &[Override::parse(text)?])
    }

    #[test]
    fn a_list_where_a_struct_is_expected_is_refused_naming_its_fields() {
        for text in ["drag=[0.1, 0.2]", "drag=Some([0.1, 0.2])", "Form.gains=[1.0, 2.0, 3.0]"] {
            let error = set_one(text).expect_err(text).to_string();
            assert!(error.contains("is a struct with the fields"), "{text}: {error}");
            assert!(error.contains("a list `[…]` names none of them"), "{text}: {error}");
        }
        let error = set_one("drag=[0.1, 0.2]").expect_err("a list").to_string();
        assert!(error.contains("linear_dyn_s_per_cm3"), "{error}");
        // The struct by its field names, and a list where a list is expected, still apply.
        let drag = "drag=Some((linear_dyn_s_per_cm3: 0.1, quadratic_g_per_cm3: 0.2))";
        assert!(set_one(drag).is_ok());
        assert!(!is_list("(0.1, 0.2)") && is_list(" Some( [1]) ") && !is_list("Some(x)"));
    }

    /// An optional field left out of the scenario's text while `None` can be set; a misspelt
    /// one is still refused by name.
    #[test]
    fn an_optional_field_left_out_while_none_can_be_set() {
        let set = set_one("phases[2].Thigmotaxis.parameters.replay=Some((file: \"field.csv\"))")
            .expect("applies");
        let replayed = format!("{:?}", set.phases[2]);
        assert!(replayed.contains("field.csv"), "{replayed}");
        assert_eq!(set_one("Thigmotaxis.parameters.replay=None").expect("applies"), scenario());
        let misspelt = set_one("Thigmotaxis.parameters.replayy=Some((file: \"f.csv\"))")
            .expect_err("no such field")
            .to_string();
        assert!(misspelt.contains("no field `replayy` here"), "{misspelt}");
    }

    #[test]
    fn a_top_level_value_changes_and_nothing_else() {
        let before = scenario();
        let after = set_one("time_step_s=0.02").expect("applies");
        assert_eq!(after.time_step_s, 0.02);
        assert_eq!(Scenario { time_step_s: before.time_step_s, ..after }, before);
    }

    #[test]
    fn kind_wide_and_indexed_phase_paths() {
        let all = set_one("Thigmotaxis.parameters.tail_pull_dyn=0").expect("applies");
        let one = set_one("phases[2].Thigmotaxis.parameters.tail_pull_dyn=5.5").expect("applies");
        let pulls = |s: &Scenario| -> Vec<String> {
            s.phases.iter().map(|p| format!("{p:?}")).filter(|p| p.contains("tail_pull")).collect()
        };
        assert!(pulls(&all).iter().all(|p| p.contains("tail_pull_dyn: 0.0")), "{:?}", pulls(&all));
        let one = pulls(&one);
        assert!(one[0].contains("tail_pull_dyn: 20.0") && one[1].contains("tail_pull_dyn: 5.5"));
        let drag = set_one("drag.quadratic_g_per_cm3=1.0").expect("applies");
        assert_eq!(drag.drag.map(|d| d.quadratic_g_per_cm3), Some(1.0));
        let sparse = set_one("backend=SparseMaximal").expect("applies");
        assert_eq!(sparse.backend, hagfish_sim::DynamicsBackend::SparseMaximal);
        assert_eq!(set_one("drag=None").expect("applies").drag, None);
    }

    #[test]
    fn structs_variants_and_whole_phases_as_in_the_scenario_files() {
        let drag = set_one("drag=Some((linear_dyn_s_per_cm3: 0.25, quadratic_g_per_cm3: 1.0))")
            .expect("applies");
        let drag = drag.drag.expect("drag");
        assert_eq!((drag.linear_dyn_s_per_cm3, drag.quadratic_g_per_cm3), (0.25, 1.0));
        let before = scenario();
        let hold = set_one("phases[0]=Hold(2.5)").expect("applies");
        assert_eq!(format!("{:?}", hold.phases[0]), "Hold(2.5)");
        assert_eq!(hold.phases[1..], before.phases[1..]);
        let head = set_one("phases[2].Thigmotaxis.parameters.head=(v_a: -1.0, v_b: 1.0)")
            .expect("applies");
        let positional =
            set_one("phases[2].Thigmotaxis.parameters.head=(-1.0, 1.0)").expect("applies");
        assert_eq!(head, positional);
        let missing = set_one("phases[2].Thigmotaxis.parameters.head=(v_a: -1.0)")
            .expect_err("a struct without a field");
        assert!(missing.to_string().contains("missing field `v_b`"), "{missing}");
    }

    #[test]
    fn bad_paths_values_and_types_name_the_override() {
        let message = |text: &str| set_one(text).expect_err(text).to_string();
        assert!(message("time_stepp=1").contains("--set time_stepp=1: no field `time_stepp`"));
        assert!(message("time_step_s=abc").contains("wrong value for time_step_s"));
        assert!(message("time_step_s").contains("expected PATH=VALUE"));
        assert!(message("Form.gains.kp=1").contains("no field `kp`"));
        assert!(message("phases[9].Form=1").contains("no [9]"));
        assert!(message("duration_s=-inf").contains("the value: expected a finite number"));
        assert!(message("duration_s=1..2").contains("wrong value for duration_s"));
        let nested = message("time_step_s=Some(Some(0.01))");
        assert!(nested.contains("the value: expected one `Some`"), "{nested}");
        let deep = message(&format!("time_step_s={}", "[".repeat(15_000)));
        assert!(deep.contains("the value: expected at most 64 levels of nesting"), "{deep}");
        assert!(message("time_step_s=NaN").contains("the value: expected a finite number"));
        let bare = message("phases[0]=Hold");
        assert!(bare.contains("`Hold` holds a value: write it as `Hold(…)`"), "{bare}");
        let unknown = message("backend=Fast");
        assert!(unknown.contains("unknown variant `Fast`") && !unknown.contains("holds"));
    }
}
