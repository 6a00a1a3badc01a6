//! One output file of a run: its path and a buffered writer, created empty or reopened at a
//! given length (to resume a run from a checkpoint), with every I/O error naming the file.

use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use crate::error::SimError;

/// An output file being appended to.
#[derive(Debug)]
pub(crate) struct OutputFile {
    path: PathBuf,
    writer: BufWriter<File>,
}

impl OutputFile {
    /// Creates (or empties) the file at `path`.
    pub(crate) fn create(path: &Path) -> Result<Self, SimError> {
        let file = File::create(path).map_err(|source| output(path, source))?;
        Ok(Self { path: path.to_path_buf(), writer: BufWriter::new(file) })
    }

    /// Opens the existing file at `path`, cuts it to `length` bytes and appends from there.
    pub(crate) fn reopen(path: &Path, length: u64) -> Result<Self, SimError> {
        let fail = |source| output(path, source);
        let mut file = OpenOptions::new().read(true).write(true).open(path).map_err(fail)?;
        let actual = file.metadata().map_err(fail)?.len();
        if actual < length {
            return Err(output(
                path,
                std::io::Error::new(
                    std::io::ErrorKind::UnexpectedEof,
                    format!("{actual} bytes, the checkpoint expects at least {length}"),
                ),
            ));
        }
        file.set_len(length).map_err(fail)?;
        file.seek(SeekFrom::End(0)).map_err(fail)?;
        Ok(Self { path: path.to_path_buf(), writer: BufWriter::new(file) })
    }

    /// The file's path.
    pub(crate) fn path(&self) -> &Path {
        &self.path
    }

    /// Appends `line` and a newline (buffered).
    pub(crate) fn line(&mut self, line: std::fmt::Arguments<'_>) -> Result<(), SimError> {
        writeln!(self.writer, "{line}").map_err(|source| output(&self.path, source))
    }

    /// Appends raw bytes (buffered).
    pub(crate) fn bytes(&mut self, bytes: &[u8]) -> Result<(), SimError> {
        self.writer.write_all(bytes).map_err(|source| output(&self.path, source))
    }

    /// Writes `bytes` at `offset` from the start and returns to the end (flushes first).
    pub(crate) fn overwrite(&mut self, offset: u64, bytes: &[u8]) -> Result<(), SimError> {
        let fail = |source| output(&self.path, source);
        self.writer.seek(SeekFrom::Start(offset)).map_err(fail)?;
        self.writer.write_all(bytes).map_err(fail)?;
        self.writer.seek(SeekFrom::End(0)).map_err(fail)?;
        Ok(())
    }

    /// Writes everything buffered to the file.
    pub(crate) fn flush(&mut self) -> Result<(), SimError> {
        self.writer.flush().map_err(|source| output(&self.path, source))
    }

    /// The file's length in bytes, buffered bytes included.
    pub(crate) fn len(&mut self) -> Result<u64, SimError> {
        self.writer.stream_position().map_err(|source| output(&self.path, source))
    }
}

fn output(path: &Path, source: std::io::Error) -> SimError {
    SimError::Output { path: path.to_path_buf(), source }
}
