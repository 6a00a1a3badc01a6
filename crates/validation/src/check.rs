//! One row of the validation table.

/// A measured value against its reference: what was set up, the formula and its source, and
/// the tolerance the test asserts.
#[derive(Clone, Debug, PartialEq)]
pub struct Check {
    /// Short name, e.g. "cantilever, small load".
    pub name: String,
    /// The set-up: body, load, resolution.
    pub setup: String,
    /// The formula or reference the value is compared with.
    pub formula: &'static str,
    /// Where the formula comes from.
    pub source: &'static str,
    /// The reference value (unit in `unit`).
    pub expected: f64,
    /// The simulator's value.
    pub measured: f64,
    /// Unit of both values.
    pub unit: &'static str,
    /// The largest relative error accepted, `|measured − expected| / |expected|`.
    pub tolerance: f64,
}

impl Check {
    /// `|measured − expected| / |expected|` (the absolute error if `expected` is 0).
    pub fn error(&self) -> f64 {
        let scale = if self.expected == 0.0 { 1.0 } else { self.expected.abs() };
        (self.measured - self.expected).abs() / scale
    }

    /// True when the error is within the tolerance (false for a non-finite value).
    pub fn passes(&self) -> bool {
        self.error() <= self.tolerance
    }

    /// One Markdown table row: name, set-up, formula, source, expected, measured, error,
    /// tolerance.
    pub fn markdown_row(&self) -> String {
        format!(
            "| {} | {} | {} | {} | {:.6} {u} | {:.6} {u} | {:.2e} | {:.0e} |",
            self.name,
            self.setup,
            self.formula,
            self.source,
            self.expected,
            self.measured,
            self.error(),
            self.tolerance,
            u = self.unit,
        )
    }
}
