//! Reading RON data files: parse errors and physically invalid values both come back as an
//! [`AnatomyError`] with `file:line:column`. Used for biometrics here and for scenarios by
//! `hagfish-sim`, so every data file of the project reports errors the same way.

use std::path::Path;

use serde::de::DeserializeOwned;

use crate::biometrics::Biometrics;
use crate::error::{AnatomyError, Field, Origin};
use crate::locate::{locate, locate_literal, position};

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
        Self::parse(&read_data_file(path)?, path)
    }

    /// Parses RON `bytes`; `path` names the source in messages. A leading UTF-8 byte order
    /// mark is accepted (and dropped).
    pub fn parse(bytes: &[u8], path: &Path) -> Result<Self, AnatomyError> {
        let bytes = bytes.strip_prefix(UTF8_BOM).unwrap_or(bytes);
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

    /// Where the `key` whose value is the string `value` sits in the file (the whole file if
    /// no `key` has it, e.g. a value given by an override): `file: "plan.ron"` among the
    /// `file` keys of knot plans, modal bases and replays.
    pub fn locate_string(&self, key: &str, value: &str) -> Origin {
        locate_literal(&self.text, &self.path, key, &format!("{value:?}"))
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

/// The UTF-8 byte order mark, which some editors put at the start of a text file.
const UTF8_BOM: &[u8] = b"\xEF\xBB\xBF";

/// The most bytes a data file (scenario, body, checkpoint, grid) may have: 64 MiB, far above
/// any real one (a checkpoint of 100 000 bodies is ≈ 8 MB), so a wrong path (a device, a
/// huge log) is refused before it fills the memory.
pub const MAX_DATA_FILE_BYTES: u64 = 64 << 20;

/// The bytes of the data file at `path`: a regular file (a link to one included) of at most
/// [`MAX_DATA_FILE_BYTES`], read to its end but never beyond that bound (a file growing while
/// read included).
///
/// # Errors
/// [`AnatomyError::Io`] naming the path: missing or unreadable, not a regular file (a device
/// such as `/dev/zero`, a FIFO, a directory), or larger than the bound.
pub fn read_data_file(path: &Path) -> Result<Vec<u8>, AnatomyError> {
    read_bounded(path, MAX_DATA_FILE_BYTES)
        .map_err(|source| AnatomyError::Io { path: path.to_path_buf(), source })
}

/// The bytes of the regular file at `path` if it has at most `limit` bytes.
///
/// # Errors
/// As [`read_data_file`], as an `io::Error` that says what is wrong.
pub fn read_bounded(path: &Path, limit: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    let file = std::fs::File::open(path)?;
    let metadata = file.metadata()?;
    if !metadata.is_file() {
        return Err(std::io::Error::other(
            "not a regular file (a device, FIFO, socket or directory); give a file",
        ));
    }
    let too_large = || {
        std::io::Error::other(format!(
            "larger than {limit} bytes, the most a data file may have; is it the right file?"
        ))
    };
    if metadata.len() > limit {
        return Err(too_large());
    }
    let mut bytes = Vec::with_capacity(usize::try_from(metadata.len()).unwrap_or(0));
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(bytes)
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

#[cfg(test)]
mod tests {
    use super::*;

    fn es103() -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/hagfish/es103.ron")
    }

    #[test]
    fn a_byte_order_mark_is_accepted() -> Result<(), AnatomyError> {
        let bytes =
            std::fs::read(es103()).map_err(|source| AnatomyError::Io { path: es103(), source })?;
        let plain = Biometrics::from_ron(&bytes, &es103())?;
        let marked = [UTF8_BOM, &bytes].concat();
        assert_eq!(Biometrics::from_ron(&marked, &es103())?, plain);
        assert!(crate::Body::from_ron(&marked, &es103()).is_ok());
        Ok(())
    }

    #[test]
    fn a_device_or_a_file_over_the_bound_is_refused_before_it_is_read() {
        let error = Biometrics::load("/dev/zero").expect_err("a device").to_string();
        assert!(error.contains("/dev/zero: cannot read the file: not a regular file"), "{error}");
        let error = Biometrics::load("/tmp").expect_err("a directory").to_string();
        assert!(error.contains("not a regular file"), "{error}");
        let error = read_bounded(&es103(), 100).expect_err("over the bound").to_string();
        assert!(error.contains("larger than 100 bytes"), "{error}");
        assert!(read_bounded(&es103(), MAX_DATA_FILE_BYTES).is_ok());
    }
}
