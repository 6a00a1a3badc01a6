//! The VALUE of a `--set PATH=VALUE` override: the RON notation of the scenario files, read
//! into the serde data model the scenario is overridden in (`overrides.rs`).
//!
//! Grammar (whitespace allowed between tokens):
//! - `None`, `true`, `false`, a number (`2`, `-0.5`, `1e-3`; finite), a quoted string
//!   (`"../hagfish/es103.ron"`, with `\"` and `\\` escapes);
//! - `Some(VALUE)`: the value itself (serde writes `Some(x)` as `x`);
//! - an identifier (an enum variant without data: `SparseMaximal`);
//! - `Variant(VALUE, …)`: an enum variant with data, `{"Variant": VALUE}` for one value and
//!   `{"Variant": [VALUE, …]}` for several (`Trefoil(Left)`, `Tie((knot: FigureEight, at:
//!   0.31))`);
//! - `(VALUE, …)`: a tuple, also the fields of a struct in their order (`(0.0, 2.0)` for
//!   `head`);
//! - `(name: VALUE, …)`: a struct by field names (`Some((linear_dyn_s_per_cm3: 0.0,
//!   quadratic_g_per_cm3: 1.0))`);
//! - `[VALUE, …]`: a list.
//!
//! A trailing comma is allowed in tuples, structs and lists, as in RON. An error names the
//! column (from 1) where the text stops fitting.

use serde_json::{Map, Value};

/// Parses an override's VALUE (see the module documentation).
///
/// # Errors
/// What was expected and the column (from 1, in characters) where the text departs from it.
pub fn parse_override_value(text: &str) -> Result<Value, String> {
    let mut parser = Parser { chars: text.chars().collect(), at: 0 };
    let value = parser.value()?;
    parser.skip_space();
    if parser.at < parser.chars.len() {
        return Err(parser.expected("the end of the value"));
    }
    Ok(value)
}

/// Whether `c` can start an identifier: a letter or an underscore.
fn starts_identifier(c: char) -> bool {
    c.is_alphabetic() || c == '_'
}

/// A cursor over the value's characters.
struct Parser {
    chars: Vec<char>,
    at: usize,
}

impl Parser {
    fn value(&mut self) -> Result<Value, String> {
        self.skip_space();
        match self.peek() {
            Some('(') => self.parenthesised(),
            Some('[') => {
                self.at += 1;
                self.sequence(']').map(Value::Array)
            }
            Some('"') => self.string(),
            Some(c) if starts_identifier(c) => self.named(),
            Some(c) if c.is_ascii_digit() || matches!(c, '-' | '+' | '.') => self.number(),
            _ => Err(self.expected(
                "a number, true/false, None, Some(…), a quoted string, an identifier, \
                 Variant(…), a tuple (…), a struct (name: …) or a list […]",
            )),
        }
    }

    /// An identifier, and what it starts: `None`, `true`, `false`, `Some(…)`, `Variant(…)`.
    fn named(&mut self) -> Result<Value, String> {
        let name = self.identifier();
        self.skip_space();
        if self.peek() != Some('(') {
            return Ok(match name.as_str() {
                "None" => Value::Null,
                "true" => Value::Bool(true),
                "false" => Value::Bool(false),
                _ => Value::String(name),
            });
        }
        let start = self.at;
        self.at += 1;
        let mut items = self.sequence(')')?;
        match (name.as_str(), items.len()) {
            ("Some", 1) => Ok(items.remove(0)),
            ("Some", _) => {
                self.at = start;
                Err(self.expected("one value in Some(…)"))
            }
            (_, 0) => Ok(Value::String(name)),
            (_, 1) => Ok(Value::Object(Map::from_iter([(name, items.remove(0))]))),
            _ => Ok(Value::Object(Map::from_iter([(name, Value::Array(items))]))),
        }
    }

    /// `(…)`: a struct when its first item is `name:`, else a tuple.
    fn parenthesised(&mut self) -> Result<Value, String> {
        self.at += 1;
        let rewind = self.at;
        self.skip_space();
        if self.peek().is_some_and(starts_identifier) {
            self.identifier();
            self.skip_space();
            if self.peek() == Some(':') {
                self.at = rewind;
                return self.fields();
            }
        }
        self.at = rewind;
        self.sequence(')').map(Value::Array)
    }

    /// `name: VALUE, …)` after the opening parenthesis.
    fn fields(&mut self) -> Result<Value, String> {
        let mut fields = Map::new();
        loop {
            self.skip_space();
            if self.eat(')') {
                return Ok(Value::Object(fields));
            }
            if !self.peek().is_some_and(starts_identifier) {
                return Err(self.expected("a field name or `)`"));
            }
            let name = self.identifier();
            self.skip_space();
            if !self.eat(':') {
                return Err(self.expected(&format!("`:` after the field name `{name}`")));
            }
            let value = self.value()?;
            if fields.insert(name.clone(), value).is_some() {
                return Err(self.expected(&format!("the field `{name}` only once")));
            }
            self.skip_space();
            if !self.eat(',') && self.peek() != Some(')') {
                return Err(self.expected("`,` or `)`"));
            }
        }
    }

    /// `VALUE, …` up to `close`, after the opening bracket.
    fn sequence(&mut self, close: char) -> Result<Vec<Value>, String> {
        let mut items = Vec::new();
        loop {
            self.skip_space();
            if self.eat(close) {
                return Ok(items);
            }
            items.push(self.value()?);
            self.skip_space();
            if !self.eat(',') && self.peek() != Some(close) {
                return Err(self.expected(&format!("`,` or `{close}`")));
            }
        }
    }

    fn string(&mut self) -> Result<Value, String> {
        let start = self.at;
        self.at += 1;
        let mut text = String::new();
        while let Some(c) = self.peek() {
            self.at += 1;
            match c {
                '"' => return Ok(Value::String(text)),
                '\\' => match self.peek() {
                    Some(escaped @ ('"' | '\\')) => {
                        self.at += 1;
                        text.push(escaped);
                    }
                    _ => return Err(self.expected("`\\\"` or `\\\\` after a backslash")),
                },
                _ => text.push(c),
            }
        }
        self.at = start;
        Err(self.expected("a closing `\"` for the string starting here"))
    }

    fn number(&mut self) -> Result<Value, String> {
        let start = self.at;
        while self.peek().is_some_and(|c| c.is_ascii_alphanumeric() || matches!(c, '-' | '+' | '.'))
        {
            self.at += 1;
        }
        let text: String = self.chars[start..self.at].iter().collect();
        if let Ok(integer) = text.parse::<i64>() {
            return Ok(Value::from(integer));
        }
        let finite = text.parse::<f64>().ok().and_then(serde_json::Number::from_f64);
        finite.map(Value::Number).ok_or_else(|| {
            self.at = start;
            self.expected(&format!("a finite number, not `{text}`"))
        })
    }

    /// Letters, digits and underscores, starting with a letter or an underscore.
    fn identifier(&mut self) -> String {
        let start = self.at;
        while self.peek().is_some_and(|c| c.is_alphanumeric() || c == '_') {
            self.at += 1;
        }
        self.chars[start..self.at].iter().collect()
    }

    fn skip_space(&mut self) {
        while self.peek().is_some_and(char::is_whitespace) {
            self.at += 1;
        }
    }

    fn peek(&self) -> Option<char> {
        self.chars.get(self.at).copied()
    }

    fn eat(&mut self, c: char) -> bool {
        let found = self.peek() == Some(c);
        self.at += usize::from(found);
        found
    }

    fn expected(&self, what: &str) -> String {
        match self.peek() {
            Some(found) => format!("expected {what} at column {}, found `{found}`", self.at + 1),
            None => format!("expected {what} at column {}, found the end", self.at + 1),
        }
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
    }

    #[test]
    fn errors_name_the_column() {
        let error = |text: &str| parse_override_value(text).expect_err(text);
        assert_eq!(error("1..2"), "expected a finite number, not `1..2` at column 1, found `1`");
        assert!(error("(a: 1, b 2)").contains("`:` after the field name `b` at column 10"));
        assert!(error("(1, 2").contains("`,` or `)` at column 6, found the end"));
        assert!(error("Some(1, 2)").contains("one value in Some(…) at column 5"));
        assert!(error("(a: 1, a: 2)").contains("the field `a` only once"));
        assert!(error("\"open").contains("closing `\"`"));
        assert!(error("1 2").contains("the end of the value at column 3"));
        assert!(error("-inf").contains("a finite number, not `-inf`"));
    }
}
