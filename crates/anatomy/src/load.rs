//! Reading a biometrics RON file: parse errors and physically invalid values both come back
//! as an [`AnatomyError`] with `file:line:column`.

use std::path::Path;

use crate::biometrics::Biometrics;
use crate::error::{AnatomyError, Origin};
use crate::locate::{locate, position};

impl Biometrics {
    /// Reads, parses and validates the RON file at `path` (see [`Biometrics::from_ron`]).
    /// A missing or unreadable file is an [`AnatomyError::Io`] naming the path.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, AnatomyError> {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|source| AnatomyError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        Self::from_ron(&bytes, path)
    }

    /// Parses RON `bytes` and validates the values ([`Biometrics::validate`]); `path` names the
    /// source in messages. Every error carries the position of the offending text: ron's
    /// position for syntax, missing and unknown fields, the value's position (found in the
    /// text) for out-of-range values.
    pub fn from_ron(bytes: &[u8], path: &Path) -> Result<Self, AnatomyError> {
        let text = std::str::from_utf8(bytes).map_err(|e| {
            let valid = String::from_utf8_lossy(&bytes[..e.valid_up_to()]);
            AnatomyError::NotUtf8 {
                at: position(&valid, path, valid.len()),
            }
        })?;
        let biometrics: Biometrics = ron::from_str(text).map_err(|e| parse_error(e, path))?;
        biometrics.validate_with(&|field| locate(text, path, field))?;
        Ok(biometrics)
    }
}

/// Maps ron's error to a typed [`AnatomyError`] at ron's start position.
fn parse_error(e: ron::error::SpannedError, path: &Path) -> AnatomyError {
    let at = Origin::Position {
        path: path.to_path_buf(),
        line: e.span.start.line,
        column: e.span.start.col,
    };
    match e.code {
        ron::Error::MissingStructField { field, .. } => AnatomyError::MissingField { at, field },
        ron::Error::NoSuchStructField {
            expected, found, ..
        } => AnatomyError::UnknownField {
            at,
            field: found,
            expected,
        },
        code => AnatomyError::Parse {
            at,
            message: code.to_string(),
        },
    }
}
