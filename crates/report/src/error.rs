//! The error of this crate: every variant names the file it concerns, and the line where
//! there is one.

use std::path::PathBuf;

/// What can stop reading a run directory or writing its pictures, report and exports.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A file of the run directory could not be read.
    #[error("{}: cannot read: {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A line of a CSV file is malformed (1-based line number).
    #[error("{}:{line}: {what}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// The line (1 = header).
        line: usize,
        /// What is wrong.
        what: String,
    },
    /// A file of the run directory is well formed but unusable (e.g. it has no frame).
    #[error("{}: {what}", path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        what: String,
    },
    /// An output file or directory could not be written.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// A picture could not be drawn or encoded.
    #[error("{}: cannot draw: {what}", path.display())]
    Draw {
        /// The picture's file.
        path: PathBuf,
        /// What the drawing or encoding library said.
        what: String,
    },
}

impl ReportError {
    /// A [`ReportError::Write`] for `path`, for use with `map_err`.
    pub fn write(path: &std::path::Path) -> impl FnOnce(std::io::Error) -> Self + '_ {
        move |source| Self::Write { path: path.to_path_buf(), source }
    }

    /// A [`ReportError::Draw`] for `path`, for use with `map_err`.
    pub fn draw<E: std::fmt::Display>(path: &std::path::Path) -> impl FnOnce(E) -> Self + '_ {
        move |e| Self::Draw { path: path.to_path_buf(), what: e.to_string() }
    }
}
