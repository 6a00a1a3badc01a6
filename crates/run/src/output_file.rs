//! One output file of a run: its path, the file and the bytes of the frame being written,
//! created empty or reopened at a given length (to resume a run from a checkpoint), with
//! every I/O error naming the file.
//!
//! Lines are gathered in memory and written by [`OutputFile::flush`] in one `write` call per
//! frame, so a run killed between two frames leaves complete rows only. Killed during that
//! write, a file may end in part of a frame, even part of a row: Linux stops a write between
//! pages when SIGKILL arrives. The checkpoint records how far every file is whole, a resume
//! cuts the files there, and the report's reader leaves out a last line without its newline.

use std::fs::{File, OpenOptions};
use std::io::{Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use crate::error::RunError;

/// An output file being appended to.
#[derive(Debug)]
pub(crate) struct OutputFile {
    path: PathBuf,
    file: File,
    /// Bytes in the file.
    written: u64,
    /// Bytes gathered since the last flush.
    pending: Vec<u8>,
}

impl OutputFile {
    /// Creates the file at `path`, replacing a file or symbolic link of that name (the link
    /// itself, never what it points to).
    pub(crate) fn create(path: &Path) -> Result<Self, RunError> {
        remove_if_present(path)?;
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(path)
            .map_err(|source| output(path, source))?;
        Ok(Self { path: path.to_path_buf(), file, written: 0, pending: Vec::new() })
    }

    /// Opens the existing file at `path`, cuts it to `length` bytes and appends from there.
    pub(crate) fn reopen(path: &Path, length: u64) -> Result<Self, RunError> {
        let fail = |source| output(path, source);
        refuse_symlink(path)?;
        let mut file = OpenOptions::new().write(true).open(path).map_err(fail)?;
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
        Ok(Self { path: path.to_path_buf(), file, written: length, pending: Vec::new() })
    }

    /// The file's path.
    pub(crate) fn path(&self) -> &Path {
        &self.path
    }

    /// Appends `line` and a newline (in memory until the next flush).
    pub(crate) fn line(&mut self, line: std::fmt::Arguments<'_>) -> Result<(), RunError> {
        self.pending.write_fmt(line).map_err(|source| output(&self.path, source))?;
        self.pending.push(b'\n');
        Ok(())
    }

    /// Appends raw bytes (in memory until the next flush).
    pub(crate) fn bytes(&mut self, bytes: &[u8]) {
        self.pending.extend_from_slice(bytes);
    }

    /// Writes what was gathered, then `bytes` at `offset` from the start, and returns to the
    /// end.
    pub(crate) fn overwrite(&mut self, offset: u64, bytes: &[u8]) -> Result<(), RunError> {
        self.flush()?;
        let fail = |source| output(&self.path, source);
        self.file.seek(SeekFrom::Start(offset)).map_err(fail)?;
        self.file.write_all(bytes).map_err(fail)?;
        self.file.seek(SeekFrom::End(0)).map_err(fail)?;
        Ok(())
    }

    /// Writes everything gathered to the file in one call.
    pub(crate) fn flush(&mut self) -> Result<(), RunError> {
        if self.pending.is_empty() {
            return Ok(());
        }
        self.file.write_all(&self.pending).map_err(|source| output(&self.path, source))?;
        self.written += self.pending.len() as u64;
        self.pending.clear();
        Ok(())
    }

    /// The file's length in bytes, gathered bytes included.
    pub(crate) fn len(&self) -> u64 {
        self.written + self.pending.len() as u64
    }
}

/// Writes `bytes` as the file at `path` atomically and without following symbolic links: into
/// a new file beside it (`NAME.partial`, created exclusively), then renamed over `path`, which
/// replaces a file or a link of that name but never writes through a link. A reader sees the
/// old content or the new, never a part; a write that fails (a full disk) removes its
/// `.partial` file.
pub fn replace_file(path: &Path, bytes: &[u8]) -> Result<(), RunError> {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".partial");
    let temporary = path.with_file_name(name);
    remove_if_present(&temporary)?;
    let fail = |source| output(path, source);
    let mut file =
        OpenOptions::new().write(true).create_new(true).open(&temporary).map_err(fail)?;
    let written = file.write_all(bytes).and_then(|()| {
        drop(file);
        std::fs::rename(&temporary, path)
    });
    if let Err(source) = written {
        // A full disk or a failed rename leaves no partial file behind; removing it is all
        // that can be tried, and the write's error is the one to report.
        let _ = std::fs::remove_file(&temporary);
        return Err(fail(source));
    }
    Ok(())
}

/// Removes the file or symbolic link at `path` if there is one.
fn remove_if_present(path: &Path) -> Result<(), RunError> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(output(path, e)),
        _ => Ok(()),
    }
}

/// Refuses a symbolic link at `path`: a run appends only to files of its own.
fn refuse_symlink(path: &Path) -> Result<(), RunError> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if meta.file_type().is_symlink() => Err(output(
            path,
            std::io::Error::other("is a symbolic link; a run writes only files of its own"),
        )),
        _ => Ok(()),
    }
}

fn output(path: &Path, source: std::io::Error) -> RunError {
    RunError::Output { path: path.to_path_buf(), source }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_replacement_that_fails_leaves_no_partial_file() {
        let dir = std::env::temp_dir().join(format!("hagfish-replace-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        // A non-empty directory in the way: the rename fails after the bytes are written.
        let path = dir.join("manifest.json");
        std::fs::create_dir_all(path.join("in the way")).expect("mkdir");
        let error = replace_file(&path, b"{}").expect_err("a directory is in the way");
        assert!(error.to_string().contains("manifest.json"), "{error}");
        assert!(!dir.join("manifest.json.partial").exists(), "the partial file is left");
        std::fs::remove_dir_all(&path).expect("rmdir");
        replace_file(&path, b"{}").expect("replaced");
        assert_eq!(std::fs::read(&path).ok().as_deref(), Some(&b"{}"[..]));
        assert!(!dir.join("manifest.json.partial").exists());
        std::fs::remove_dir_all(&dir).expect("rm");
    }
}
