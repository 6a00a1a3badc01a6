//! The run directory as a whole: one process at a time (a lock), and a run replaced only when
//! asked (`--overwrite`), without losing the old one if the new one cannot start. Only the
//! program's own files are ever moved, replaced or removed; a user's files beside them, in
//! `vtk/` or `plots/` included, are left alone.

use std::fs::{File, OpenOptions, TryLockError};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::SystemTime;

use hagfish_run::{CHECKPOINT_FILE, Recorder};

use crate::CliError;
use crate::manifest::MANIFEST_FILE;
use crate::utc::iso8601;

/// The lock file of a run directory: `flock`ed while a process runs in the directory, and
/// holding that process's id and start time for the message of a second one.
pub const LOCK_FILE: &str = ".hagfish.lock";

/// Where a replaced run's files wait until the new run has started.
const SET_ASIDE: &str = ".hagfish-previous";

/// The files of a run other than the recorder's outputs and the report's.
const RUN_FILES: [&str; 6] = [
    "scenario.ron",
    MANIFEST_FILE,
    CHECKPOINT_FILE,
    "diverged.ron",
    "checkpoint.ron.partial",
    "manifest.json.partial",
];

fn failure(path: &Path, e: impl std::fmt::Display) -> CliError {
    CliError::RunDirectory { path: path.to_path_buf(), reason: e.to_string() }
}

/// A run directory locked by this process. The lock is an advisory `flock` on
/// [`LOCK_FILE`], released when this is dropped or the process ends however it ends, so a
/// lock left by a killed run is simply taken over.
#[derive(Debug)]
pub struct LockedDirectory {
    _lock: File,
}

impl LockedDirectory {
    /// Locks `directory` (created first if `create`), or says which process holds it.
    pub fn lock(directory: &Path, create: bool) -> Result<Self, CliError> {
        if create {
            std::fs::create_dir_all(directory).map_err(|e| failure(directory, e))?;
        } else if !directory.is_dir() {
            return Err(failure(directory, "no such run directory"));
        }
        let path = directory.join(LOCK_FILE);
        if path.symlink_metadata().is_ok_and(|m| m.file_type().is_symlink()) {
            return Err(failure(&path, "is a symbolic link; remove it"));
        }
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(|e| failure(&path, e))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                let holder = std::fs::read_to_string(&path).unwrap_or_default();
                return Err(failure(
                    directory,
                    format!(
                        "in use by another hagfish process ({}); wait for it to end or choose \
                         another directory",
                        holder.trim()
                    ),
                ));
            }
            Err(TryLockError::Error(e)) => return Err(failure(&path, e)),
        }
        let holder = format!("pid {}, since {}", std::process::id(), iso8601(SystemTime::now()));
        file.set_len(0).map_err(|e| failure(&path, e))?;
        file.write_all(holder.as_bytes()).map_err(|e| failure(&path, e))?;
        Ok(Self { _lock: file })
    }
}

/// Every file of an earlier run in `directory` that this program wrote (and exists).
fn own_files(directory: &Path) -> Result<Vec<PathBuf>, CliError> {
    let names = RUN_FILES.iter().copied().chain(Recorder::FILE_NAMES);
    let mut files: Vec<PathBuf> = names
        .map(|name| directory.join(name))
        .filter(|path| path.symlink_metadata().is_ok())
        .collect();
    files.extend(hagfish_report::own_files(directory)?);
    Ok(files)
}

/// The files of a run moved aside (into `.hagfish-previous/`, same relative paths) while a new run
/// is set up: [`SetAside::discard`] once it has started, [`SetAside::restore`] if it could not.
#[derive(Debug)]
pub struct SetAside {
    directory: PathBuf,
    moved: Vec<(PathBuf, PathBuf)>,
}

impl SetAside {
    /// Moves the program's files in `directory` aside; if one cannot be moved, those already
    /// moved are put back and the error is returned (the directory is as it was).
    pub fn new(directory: &Path) -> Result<Self, CliError> {
        let aside = directory.join(SET_ASIDE);
        let mut set = Self { directory: directory.to_path_buf(), moved: Vec::new() };
        if aside.symlink_metadata().is_ok() {
            std::fs::remove_dir_all(&aside).map_err(|e| failure(&aside, e))?;
        }
        for file in own_files(directory)? {
            let relative = file.strip_prefix(directory).unwrap_or(&file);
            let target = aside.join(relative);
            let moved = target
                .parent()
                .map_or(Ok(()), std::fs::create_dir_all)
                .and_then(|()| std::fs::rename(&file, &target));
            if let Err(e) = moved {
                let error = failure(&file, format!("cannot replace the earlier run: {e}"));
                set.put_back()?;
                set.discard()?;
                return Err(error);
            }
            set.moved.push((file, target));
        }
        Ok(set)
    }

    /// Removes the new run's files and puts the earlier run's back.
    pub fn restore(self) -> Result<(), CliError> {
        for file in own_files(&self.directory)? {
            std::fs::remove_file(&file).map_err(|e| failure(&file, e))?;
        }
        self.put_back()?;
        self.discard()
    }

    /// Moves the files set aside back to where they were.
    fn put_back(&self) -> Result<(), CliError> {
        for (original, target) in &self.moved {
            std::fs::rename(target, original).map_err(|e| failure(original, e))?;
        }
        Ok(())
    }

    /// Deletes the earlier run's files for good.
    pub fn discard(self) -> Result<(), CliError> {
        let aside = self.directory.join(SET_ASIDE);
        match std::fs::remove_dir_all(&aside) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(failure(&aside, e)),
            _ => Ok(()),
        }
    }
}
