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
const RUN_FILES: [&str; 8] = [
    "scenario.ron",
    MANIFEST_FILE,
    CHECKPOINT_FILE,
    "diverged.ron",
    "checkpoint.ron.partial",
    "manifest.json.partial",
    "scenario.ron.partial",
    "diverged.ron.partial",
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
        .filter(|path| path.symlink_metadata().is_ok_and(|m| !m.is_dir()))
        .collect();
    files.extend(hagfish_report::own_files(directory)?);
    Ok(files)
}

/// The files of an earlier run moved aside (into `.hagfish-previous/`, same relative paths)
/// while a new run starts in its place (`--overwrite`), so that the earlier run can be put
/// back until the new one has its first checkpoint, even after a SIGKILL at any instant:
///
/// 1. the files are moved one by one (each `rename` is atomic), then the marker
///    `.hagfish-previous/.moved` is made: without it, no file of the new run exists yet;
/// 2. the new run writes its files; once it has its first checkpoint,
///    [`SetAside::discard`] renames `.hagfish-previous` to `.hagfish-discarded` (the
///    commit: from then on the new run is the directory's, resumable) and deletes that.
///
/// [`SetAside::recover`] (run by every `hagfish run` into the directory under its lock, and by
/// `hagfish recover DIR`) undoes a replacement that stopped before its commit: without the
/// marker it moves the files back; with it, it removes the new run's files first.
#[derive(Debug)]
pub struct SetAside {
    directory: PathBuf,
    /// Whether anything was moved (a directory without an earlier run sets nothing aside).
    active: bool,
}

/// Marks a complete set-aside: every file of the earlier run is in it.
const MOVED_MARKER: &str = ".moved";

/// A set-aside being deleted after its commit ([`SetAside::discard`]).
const DISCARDED: &str = ".hagfish-discarded";

impl SetAside {
    /// Moves the program's files in `directory` aside (after recovering an earlier
    /// replacement that was stopped); if one cannot be moved, those already moved are put
    /// back and the error is returned (the directory is as it was).
    ///
    /// # Errors
    /// [`CliError::RunDirectory`] naming the file that could not be moved or put back.
    pub fn new(directory: &Path) -> Result<Self, CliError> {
        Self::recover(directory)?;
        let files = own_files(directory)?;
        let set = Self { directory: directory.to_path_buf(), active: !files.is_empty() };
        if !set.active {
            return Ok(set);
        }
        let aside = directory.join(SET_ASIDE);
        std::fs::create_dir(&aside).map_err(|e| failure(&aside, e))?;
        for file in files {
            let relative = file.strip_prefix(directory).unwrap_or(&file);
            let target = aside.join(relative);
            let moved = target
                .parent()
                .map_or(Ok(()), std::fs::create_dir_all)
                .and_then(|()| std::fs::rename(&file, &target));
            if let Err(e) = moved {
                let error = failure(&file, format!("cannot replace the earlier run: {e}"));
                Self::recover(directory)?;
                return Err(error);
            }
        }
        let marker = aside.join(MOVED_MARKER);
        File::create(&marker).map_err(|e| failure(&marker, e))?;
        Ok(set)
    }

    /// Puts back the run that a replacement stopped before its new run's first checkpoint set
    /// aside (removing the new run's files), and deletes what a committed one left; returns
    /// whether a run was put back.
    ///
    /// # Errors
    /// [`CliError::RunDirectory`] naming a file that could not be moved or removed; what
    /// was not yet put back stays in `.hagfish-previous/`, and recovering again continues.
    pub fn recover(directory: &Path) -> Result<bool, CliError> {
        remove_tree(&directory.join(DISCARDED))?;
        let aside = directory.join(SET_ASIDE);
        if aside.symlink_metadata().is_err() {
            return Ok(false);
        }
        if !aside.is_dir() || aside.symlink_metadata().is_ok_and(|m| m.file_type().is_symlink()) {
            return Err(failure(&aside, "is not a directory of the program's; remove it"));
        }
        let marker = aside.join(MOVED_MARKER);
        if marker.exists() {
            for file in own_files(directory)? {
                std::fs::remove_file(&file).map_err(|e| failure(&file, e))?;
            }
            std::fs::remove_file(&marker).map_err(|e| failure(&marker, e))?;
        }
        for relative in files_under(&aside)? {
            let (from, to) = (aside.join(&relative), directory.join(&relative));
            to.parent()
                .map_or(Ok(()), std::fs::create_dir_all)
                .and_then(|()| std::fs::rename(&from, &to))
                .map_err(|e| failure(&to, format!("cannot put the earlier run back: {e}")))?;
        }
        Self::delete(directory)?;
        Ok(true)
    }

    /// Removes the new run's files and puts the earlier run's back (the new run could not
    /// start).
    ///
    /// # Errors
    /// As [`SetAside::recover`].
    pub fn restore(self) -> Result<(), CliError> {
        if self.active {
            Self::recover(&self.directory)?;
        }
        Ok(())
    }

    /// Deletes the earlier run's files for good, once the new run has its first checkpoint:
    /// renamed away first, so that a kill while deleting leaves no half of it to put back.
    ///
    /// # Errors
    /// [`CliError::RunDirectory`] if the set-aside cannot be renamed or deleted.
    pub fn discard(self) -> Result<(), CliError> {
        if self.active { Self::delete(&self.directory) } else { Ok(()) }
    }

    /// Renames the set-aside to [`DISCARDED`] and deletes it.
    fn delete(directory: &Path) -> Result<(), CliError> {
        let (aside, discarded) = (directory.join(SET_ASIDE), directory.join(DISCARDED));
        remove_tree(&discarded)?;
        std::fs::rename(&aside, &discarded).map_err(|e| failure(&aside, e))?;
        remove_tree(&discarded)
    }
}

/// Removes the directory tree at `path` if there is one.
fn remove_tree(path: &Path) -> Result<(), CliError> {
    match std::fs::remove_dir_all(path) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(failure(path, e)),
        _ => Ok(()),
    }
}

/// The files under `root` (recursively, not following links), relative to it.
fn files_under(root: &Path) -> Result<Vec<PathBuf>, CliError> {
    let mut files = Vec::new();
    let mut pending = vec![PathBuf::new()];
    while let Some(relative) = pending.pop() {
        let dir = root.join(&relative);
        for entry in std::fs::read_dir(&dir).map_err(|e| failure(&dir, e))? {
            let entry = entry.map_err(|e| failure(&dir, e))?;
            let kind = entry.file_type().map_err(|e| failure(&entry.path(), e))?;
            let path = relative.join(entry.file_name());
            if kind.is_dir() {
                pending.push(path);
            } else {
                files.push(path);
            }
        }
    }
    files.sort();
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A directory holding an earlier run's files (and a user's), as (relative path, text).
    const EARLIER: [(&str, &str); 4] = [
        ("metrics.csv", "old metrics"),
        ("manifest.json", "old manifest"),
        ("vtk/frame_0000.vtk", "old frame"),
        ("notes.txt", "the user's"),
    ];

    fn earlier_run(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("hagfish-set-aside-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        for (path, text) in EARLIER {
            let path = dir.join(path);
            std::fs::create_dir_all(path.parent().expect("a parent")).expect("mkdir");
            std::fs::write(path, text).expect("write");
        }
        dir
    }

    fn assert_earlier_run(dir: &Path) {
        for (path, text) in EARLIER {
            let found = std::fs::read_to_string(dir.join(path)).unwrap_or_default();
            assert_eq!(found, text, "{path}");
        }
        assert!(!dir.join(SET_ASIDE).exists() && !dir.join(DISCARDED).exists());
    }

    #[test]
    fn a_set_aside_stopped_while_moving_is_put_back() -> Result<(), CliError> {
        let dir = earlier_run("moving");
        // Killed after moving one file: no marker yet, the rest still in place.
        std::fs::create_dir_all(dir.join(SET_ASIDE)).expect("mkdir");
        std::fs::rename(dir.join("metrics.csv"), dir.join(SET_ASIDE).join("metrics.csv"))
            .expect("move");
        assert!(SetAside::recover(&dir)?);
        assert_earlier_run(&dir);
        assert!(!SetAside::recover(&dir)?, "nothing left to put back");
        std::fs::remove_dir_all(&dir).expect("rm");
        Ok(())
    }

    #[test]
    fn a_new_run_stopped_before_its_commit_is_removed_and_the_earlier_put_back()
    -> Result<(), CliError> {
        let dir = earlier_run("uncommitted");
        let set = SetAside::new(&dir)?;
        assert!(dir.join(SET_ASIDE).join(MOVED_MARKER).exists());
        assert!(!dir.join("metrics.csv").exists() && dir.join("notes.txt").exists());
        // The new run's first files, then a kill (the set-aside is never discarded).
        std::fs::write(dir.join("metrics.csv"), "new metrics").expect("write");
        std::fs::write(dir.join("checkpoint.ron.partial"), "half").expect("write");
        drop(set);
        assert!(SetAside::recover(&dir)?);
        assert_earlier_run(&dir);
        assert!(!dir.join("checkpoint.ron.partial").exists());
        std::fs::remove_dir_all(&dir).expect("rm");
        Ok(())
    }

    #[test]
    fn a_committed_new_run_keeps_its_files_and_the_users() -> Result<(), CliError> {
        let dir = earlier_run("committed");
        let set = SetAside::new(&dir)?;
        std::fs::write(dir.join("metrics.csv"), "new metrics").expect("write");
        set.discard()?;
        assert!(!SetAside::recover(&dir)?);
        assert_eq!(
            std::fs::read_to_string(dir.join("metrics.csv")).ok().as_deref(),
            Some("new metrics")
        );
        assert!(!dir.join("manifest.json").exists() && !dir.join("vtk/frame_0000.vtk").exists());
        assert_eq!(
            std::fs::read_to_string(dir.join("notes.txt")).ok().as_deref(),
            Some("the user's")
        );
        assert!(!dir.join(SET_ASIDE).exists() && !dir.join(DISCARDED).exists());
        std::fs::remove_dir_all(&dir).expect("rm");
        Ok(())
    }
}
