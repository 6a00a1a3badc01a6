//! Test helpers: small files written into a per-process temporary directory, a small
//! centreline and a small run directory.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use hagfish_sim::{CENTRELINE_HEADER, FORCES_HEADER, METRICS_HEADER};

use crate::centreline::Centreline;

/// A fresh directory `name` in this process's temporary test directory.
pub fn dir(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("hagfish-report-test-{}", std::process::id())).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Writes `text` to `name` in a directory of its own (tests run in parallel and may use the
/// same file names) and returns its path.
pub fn write(name: &str, text: &str) -> PathBuf {
    static WRITTEN: AtomicUsize = AtomicUsize::new(0);
    let path = dir(&format!("file-{}", WRITTEN.fetch_add(1, Ordering::Relaxed))).join(name);
    std::fs::write(&path, text).expect("write a test file");
    path
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
pub fn synthetic(name: &str) -> PathBuf {
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
            "{f},{t:.4},form,{f},0,0_1,1.000,,,,,,,,,,,,0,0,0,0,,,,,,,Kkt,Solved,1,0,0e0"
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
