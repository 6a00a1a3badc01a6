//! Test helpers: small files written into a per-process temporary directory, and a small
//! centreline.

use std::path::PathBuf;

use crate::centreline::Centreline;

/// Writes `text` to `name` in this process's temporary test directory and returns its path.
pub fn write(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hagfish-report-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
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
