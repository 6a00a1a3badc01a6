//! Errors of loading biometrics and deriving the model, each with the place it refers to.

use std::fmt;
use std::path::PathBuf;

use hagfish_tree::TreeError;

/// Where a problem sits, for error messages: values built in code, a whole file, or a
/// position in a file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Origin {
    /// Values that did not come from a file (a [`crate::Biometrics`] built in code).
    InMemory,
    /// A file whose offending position is unknown.
    File(PathBuf),
    /// A position in a file: 1-based line and 1-based column counted in characters (the
    /// convention of `ron`'s own positions).
    Position {
        /// The file.
        path: PathBuf,
        /// Line, from 1.
        line: usize,
        /// Column in characters, from 1.
        column: usize,
    },
}

impl fmt::Display for Origin {
    /// `biometrics`, `path` or `path:line:column`, the prefix of every message.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Origin::InMemory => f.write_str("biometrics"),
            Origin::File(path) => write!(f, "{}", path.display()),
            Origin::Position { path, line, column } => {
                write!(f, "{}:{line}:{column}", path.display())
            }
        }
    }
}

/// A field of a data file, optionally one element of an array field, named as in the file
/// (`circumferences_cm[2]`, `tail_taper.tip_radius_cm`). A key that appears several times (the
/// `speed` of every `Move` step) is told apart by its occurrence in file order; a tuple variant
/// (`Hold(1.0)`) is found by its name followed by `(`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Field {
    /// The field's path in the data file, nested fields joined by `.`.
    pub name: &'static str,
    /// The element index for an array field.
    pub index: Option<usize>,
    /// Which occurrence of the key in the file (0 = the first).
    pub occurrence: usize,
}

impl Field {
    /// A whole field.
    pub fn whole(name: &'static str) -> Self {
        Self { name, index: None, occurrence: 0 }
    }

    /// Element `index` of an array field.
    pub fn element(name: &'static str, index: usize) -> Self {
        Self { name, index: Some(index), occurrence: 0 }
    }

    /// The `occurrence`-th appearance (from 0, in file order) of a key used many times.
    pub fn nth(name: &'static str, occurrence: usize) -> Self {
        Self { name, index: None, occurrence }
    }

    /// The key as written in the file: the last segment of [`Field::name`].
    pub fn key(&self) -> &'static str {
        self.name.rsplit('.').next().unwrap_or(self.name)
    }
}

impl fmt::Display for Field {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.index {
            Some(k) => write!(f, "{}[{k}]", self.name),
            None => f.write_str(self.name),
        }
    }
}

/// Everything that can go wrong from a data file to a model. Messages start with the
/// [`Origin`] (`file:line:column:`), then say what was found and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum AnatomyError {
    /// The file could not be read (missing, unreadable).
    #[error("{}: cannot read the file: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The file is not UTF-8 text; the position is that of the first invalid byte.
    #[error("{at}: the file is not valid UTF-8 text")]
    NotUtf8 {
        /// Position of the first invalid byte.
        at: Origin,
    },
    /// RON syntax or type error, as reported by `ron` (its message says what it expected).
    #[error("{at}: {message}")]
    Parse {
        /// Where the parser stopped.
        at: Origin,
        /// The parser's message.
        message: String,
    },
    /// A required field is absent.
    #[error("{at}: missing field `{field}`")]
    MissingField {
        /// Where the parser noticed (usually the end of the enclosing struct).
        at: Origin,
        /// The missing field.
        field: &'static str,
    },
    /// A field that the format does not know (a typo, or a unit-less name).
    #[error("{at}: unknown field `{field}`, expected one of: {}", expected.join(", "))]
    UnknownField {
        /// Position of the field.
        at: Origin,
        /// The field as written.
        field: String,
        /// The known fields.
        expected: &'static [&'static str],
    },
    /// A value outside its physical range (non-finite, non-positive mass, limit ∉ (0°, 180°), …).
    #[error("{at}: {field} = {} is out of range: expected {expected}", readable(*value))]
    OutOfRange {
        /// Position of the value.
        at: Origin,
        /// The field.
        field: Field,
        /// The value found.
        value: f64,
        /// The valid range.
        expected: String,
    },
    /// A mark fraction not greater than the one before it.
    #[error("{at}: {field} = {value} must be greater than the previous mark {previous}")]
    NotIncreasing {
        /// Position of the value.
        at: Origin,
        /// The field element.
        field: Field,
        /// The value found.
        value: f64,
        /// The preceding mark.
        previous: f64,
    },
    /// An array whose length differs from the number of marks.
    #[error(
        "{at}: {field} has {got} entries, expected {expected} (one per entry of mark_fractions)"
    )]
    LengthMismatch {
        /// Position of the array.
        at: Origin,
        /// The array field.
        field: Field,
        /// Its length.
        got: usize,
        /// The number of marks.
        expected: usize,
    },
    /// No measurement marks at all.
    #[error("{at}: mark_fractions is empty: at least one measurement mark is needed")]
    NoMarks {
        /// Position of the array.
        at: Origin,
    },
    /// The derived volume or density is not finite and positive (extreme lengths or radii).
    #[error(
        "derived volume {volume_cm3} cm³ gives density {density} g/cm³: both must be finite and > 0"
    )]
    DegenerateDensity {
        /// Σ π r_i² ℓ (cm³).
        volume_cm3: f64,
        /// M / volume (g/cm³).
        density: f64,
    },
    /// The kinematic tree rejected the derived bodies (only for extreme inputs that pass the
    /// field checks, e.g. masses that underflow).
    #[error("the derived model is invalid: {0}")]
    Model(#[from] TreeError),
}

/// `value` as written in a file: plain for magnitudes in [1e-4, 1e15) (and 0), in scientific
/// notation otherwise (1e-300, not three hundred zeros).
fn readable(value: f64) -> String {
    let magnitude = value.abs();
    if magnitude == 0.0 || !magnitude.is_finite() || (1e-4..1e15).contains(&magnitude) {
        value.to_string()
    } else {
        format!("{value:e}")
    }
}
