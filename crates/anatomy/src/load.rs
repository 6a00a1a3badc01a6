//! Reading RON data files: parse errors and physically invalid values both come back as an
//! [`AnatomyError`] with `file:line:column`. Used for biometrics here and for scenarios by
//! `hagfish-sim`, so every data file of the project reports errors the same way.

use std::path::Path;

use serde::de::DeserializeOwned;

use crate::biometrics::Biometrics;
use crate::error::{AnatomyError, Field, Origin};
use crate::locate::{locate, position};

/// A parsed RON data file that keeps its text, so values rejected after parsing can still be
/// reported at their `file:line:column`.
#[derive(Debug, Clone)]
pub struct DataFile<T> {
    /// The parsed value.
    pub value: T,
    /// The file's text.
    pub text: String,
    /// The file's path (as given).
    pub path: std::path::PathBuf,
}

impl<T: DeserializeOwned> DataFile<T> {
    /// Reads and parses the RON file at `path`. A missing or unreadable file is an
    /// [`AnatomyError::Io`] naming the path; syntax, type, missing and unknown fields carry
    /// ron's position.
    pub fn read(path: impl AsRef<Path>) -> Result<Self, AnatomyError> {
        let path = path.as_ref();
        let bytes = std::fs::read(path)
            .map_err(|source| AnatomyError::Io { path: path.to_path_buf(), source })?;
        Self::parse(&bytes, path)
    }

    /// Parses RON `bytes`; `path` names the source in messages.
    pub fn parse(bytes: &[u8], path: &Path) -> Result<Self, AnatomyError> {
        let text = std::str::from_utf8(bytes).map_err(|e| {
            let valid = String::from_utf8_lossy(&bytes[..e.valid_up_to()]);
            AnatomyError::NotUtf8 { at: position(&valid, path, valid.len()) }
        })?;
        let value: T = ron::from_str(text).map_err(|e| parse_error(e, path))?;
        Ok(Self { value, text: text.to_owned(), path: path.to_path_buf() })
    }

    /// Where `field`'s value sits in the file (the whole file if it cannot be found, e.g. a
    /// defaulted field).
    pub fn locate(&self, field: &Field) -> Origin {
        locate(&self.text, &self.path, field)
    }
}

impl Biometrics {
    /// Reads, parses and validates the RON file at `path` (see [`Biometrics::from_ron`]).
    /// A missing or unreadable file is an [`AnatomyError::Io`] naming the path.
    pub fn load(path: impl AsRef<Path>) -> Result<Self, AnatomyError> {
        let file = DataFile::<Biometrics>::read(path)?;
        file.value.validate_with(&|field| file.locate(field))?;
        Ok(file.value)
    }

    /// Parses RON `bytes` and validates the values ([`Biometrics::validate`]); `path` names the
    /// source in messages. Every error carries the position of the offending text: ron's
    /// position for syntax, missing and unknown fields, the value's position (found in the
    /// text) for out-of-range values.
    pub fn from_ron(bytes: &[u8], path: &Path) -> Result<Self, AnatomyError> {
        let file = DataFile::<Biometrics>::parse(bytes, path)?;
        file.value.validate_with(&|field| file.locate(field))?;
        Ok(file.value)
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
        ron::Error::NoSuchStructField { expected, found, .. } => {
            AnatomyError::UnknownField { at, field: found, expected }
        }
        code => AnatomyError::Parse { at, message: code.to_string() },
    }
}
