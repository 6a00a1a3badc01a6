//! What the fuzz targets share: a scratch copy of the shipped scenarios and body (so that a
//! fuzzed file resolves its relative paths as a user's would), and the refusal-only run
//! request through which every scenario input passes as `hagfish run` takes it.
//!
//! A target succeeds on every input that returns, error or not; a panic, an abort, a run
//! over libFuzzer's `-timeout` or an allocation over its `-malloc_limit_mb` is a finding.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::sync::atomic::AtomicBool;

use hagfish::runner::{Existing, RunRequest, Source, run_into_directory};
use hagfish_scenario::Override;

/// The scratch folder of this process: `scenarios/` (thesis.ron, tie.ron), `hagfish/`
/// (es103.ron), `knots/` and the inputs written by the targets.
pub fn scratch() -> &'static Path {
    static SCRATCH: OnceLock<PathBuf> = OnceLock::new();
    SCRATCH.get_or_init(|| {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join("data");
        let dir = std::env::temp_dir().join(format!("hagfish-fuzz-{}", std::process::id()));
        for sub in ["scenarios", "hagfish", "knots", "sweep"] {
            std::fs::create_dir_all(dir.join(sub)).expect("a scratch folder");
        }
        for file in ["scenarios/thesis.ron", "scenarios/tie.ron", "hagfish/es103.ron"] {
            std::fs::copy(root.join(file), dir.join(file)).expect("the shipped files");
        }
        dir
    })
}

/// Writes `data` to `name` under the scratch folder and returns its path.
pub fn write(name: &str, data: &[u8]) -> PathBuf {
    let path = scratch().join(name);
    std::fs::write(&path, data).expect("a writable scratch folder");
    path
}

/// `hagfish run SCENARIO --out DIR --max-steps 0 [--set …]` as a library call: everything a
/// run checks before it starts (scenario, body, overrides, plan files, the memory estimate),
/// then the refusal of the step cap. The error, if any, is formatted as the CLI prints it.
pub fn refused_run(scenario: &Path, overrides: &[Override]) {
    let out = scratch().join("out");
    let request = RunRequest {
        source: Source::Scenario { path: scenario, overrides },
        directory: &out,
        existing: Existing::Refuse,
        stop_after_frame: Some(0),
        max_steps: Some(0),
    };
    let stop = AtomicBool::new(true);
    match run_into_directory(&request, &stop, &mut |_| {}) {
        Ok(_) => {}
        Err(e) => drop(e.to_string()),
    }
    // A scenario that needs no step at all runs; the next input starts afresh.
    if out.exists() {
        std::fs::remove_dir_all(&out).expect("the scratch run removed");
    }
}
