//! Test helpers: small files written into temporary directories that remove themselves, a
//! small centreline and a small run directory.

use std::fmt::Write as _;
use std::ops::Deref;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use hagfish_run::{CENTRELINE_HEADER, FORCES_HEADER, METRICS_HEADER};

use crate::centreline::Centreline;

/// A temporary directory, removed with everything in it when dropped.
pub struct TestDir(PathBuf);

impl Deref for TestDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for TestDir {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for TestDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A file in a [`TestDir`] of its own, removed with it.
pub struct TestFile {
    path: PathBuf,
    _dir: TestDir,
}

impl Deref for TestFile {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for TestFile {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

/// A fresh directory for `name`, unique to this process and call (tests run in parallel).
pub fn dir(name: &str) -> TestDir {
    static MADE: AtomicUsize = AtomicUsize::new(0);
    let unique = format!(
        "hagfish-report-test-{}-{}-{name}",
        std::process::id(),
        MADE.fetch_add(1, Ordering::Relaxed)
    );
    let dir = std::env::temp_dir().join(unique);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    TestDir(dir)
}

/// Writes `text` to `name` in a directory of its own and returns the file.
pub fn write(name: &str, text: &str) -> TestFile {
    let dir = dir("file");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write a test file");
    TestFile { path, _dir: dir }
}

/// A centreline of 3 bodies in 2 frames (t = 0 and 0.5 s): straight along x, then bent.
pub fn two_frames() -> Centreline {
    Centreline {
        times: vec![0.0, 0.5],
        bodies: 3,
        points: vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 1.5, -0.25],
        ],
    }
}

/// A run directory of 3 frames of 4 bodies with the headers `hagfish run` writes.
pub fn synthetic(name: &str) -> TestDir {
    let dir = dir(name);
    let (mut centreline, mut metrics, mut forces) = (
        format!("{CENTRELINE_HEADER}\n"),
        format!("{METRICS_HEADER}\n"),
        format!("{FORCES_HEADER}\n"),
    );
    for f in 0..3 {
        let t = 0.1 * f as f64;
        for b in 0..4 {
            let _ = writeln!(centreline, "{f},{t:.4},{b},{},{},0", b as f64, (f * b) as f64);
        }
        let _ = writeln!(
            metrics,
            "{f},{t:.4},form,{f},0,0_1,1.000,,,,,,,,,,,,0,0,0,0,0,,,,,,,Kkt,Solved,1,0,0e0,,,,,,"
        );
        for j in 0..2 {
            for (axis, group) in [("X", "thigmo"), ("Y", "thigmo"), ("Y", "limit")] {
                let _ = writeln!(forces, "{f},{t:.4},{j},{axis},{group},{}", f + j);
            }
        }
    }
    for (file, text) in
        [("centreline.csv", centreline), ("metrics.csv", metrics), ("forces.csv", forces)]
    {
        std::fs::write(dir.join(file), text).expect("write");
    }
    dir
}
