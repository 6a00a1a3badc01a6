//! Helpers shared by the end-to-end tests: running the built `hagfish`, fresh directories,
//! and reading run directories.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root.
pub const ROOT: &str = env!("CARGO_MANIFEST_DIR");

/// A fresh (empty) directory `name` under the tests' temporary directory.
pub fn fresh_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temporary directory");
    dir
}

/// The `hagfish` command with `args`.
pub fn hagfish<I, S>(args: I) -> Command
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    let mut command = Command::new(env!("CARGO_BIN_EXE_hagfish"));
    command.args(args);
    command
}

/// Runs `hagfish` with `args` to the end.
pub fn run_hagfish<I, S>(args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    hagfish(args).output().expect("hagfish runs")
}

/// Runs the scenario `scenario` (a path from the repository root) quietly into a fresh
/// directory `name` with the `--set` values `sets`, asserts that it succeeds, and returns the
/// run directory.
pub fn run_scenario(name: &str, scenario: &str, sets: &[String]) -> PathBuf {
    let dir = fresh_dir(name);
    let scenario = format!("{ROOT}/{scenario}");
    let out = dir.to_string_lossy().into_owned();
    let mut args = vec!["run", &scenario, "--quiet", "--out", &out];
    for set in sets {
        args.extend(["--set", set]);
    }
    let output = run_hagfish(&args);
    assert!(output.status.success(), "{name}: {}", code_and_stderr(&output).1);
    dir
}

/// Checks that the run in `stopped` was interrupted, resumes it to the end and asserts that
/// each of `files` then holds the same bytes as in the uninterrupted run `straight`.
pub fn assert_resumes_to_the_same_bytes(straight: &Path, stopped: &Path, files: &[&str]) {
    assert_eq!(manifest(stopped)["status"], "interrupted");
    let resumed = run_hagfish(["run", "--resume", &stopped.to_string_lossy(), "--quiet"]);
    assert!(resumed.status.success(), "{}", code_and_stderr(&resumed).1);
    for file in files {
        let (a, b) = (std::fs::read(straight.join(file)), std::fs::read(stopped.join(file)));
        assert!(a.expect(file) == b.expect(file), "{file} differs after the resume");
    }
}

/// The exit code and stderr of `output`.
pub fn code_and_stderr(output: &Output) -> (Option<i32>, String) {
    (output.status.code(), String::from_utf8_lossy(&output.stderr).into_owned())
}

/// ES103's biometrics file with `edits` (text replacements) applied, written into `dir` as
/// `name.ron`.
pub fn es103_with(dir: &Path, name: &str, edits: &[(&str, String)]) -> PathBuf {
    let es103 =
        std::fs::read_to_string(format!("{ROOT}/data/hagfish/es103.ron")).expect("es103.ron");
    let text = hagfish_bench_support::edited(&es103, edits).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join(format!("{name}.ron"));
    std::fs::write(&path, text).expect("write a body");
    path
}

/// `manifest.json` of a run directory.
pub fn manifest(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("manifest.json")).expect("manifest.json");
    serde_json::from_str(&text).expect("manifest.json is JSON")
}

/// The rows of a CSV file, split at commas, without the header; asserts that the file ends
/// with a newline and that every row has as many fields as the header.
pub fn csv_rows(path: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).expect("a CSV file");
    assert!(text.ends_with('\n'), "{} ends in a partial row", path.display());
    complete_rows(path)
}

/// The complete rows of a CSV file, as [`csv_rows`], but a last line without its newline is
/// left out: part of a row that a killed run was writing (Linux stops a write between pages
/// when SIGKILL arrives).
pub fn complete_rows(path: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).expect("a CSV file");
    let complete = &text[..text.rfind('\n').map_or(0, |end| end + 1)];
    let mut lines = complete.lines();
    let width = lines.next().expect("a header").split(',').count();
    lines
        .map(|line| {
            let row: Vec<String> = line.split(',').map(str::to_owned).collect();
            assert_eq!(row.len(), width, "{}: row {line}", path.display());
            row
        })
        .collect()
}

/// The frame index (first column) of every row.
pub fn frames_of(rows: &[Vec<String>]) -> Vec<usize> {
    rows.iter().map(|r| r[0].parse().expect("a frame index")).collect()
}

/// Sends SIGTERM to `child` (with `kill`, as a user or a cluster scheduler would).
pub fn terminate(child: &std::process::Child) {
    let term =
        Command::new("kill").args(["-TERM", &child.id().to_string()]).status().expect("kill runs");
    assert!(term.success());
}

/// `metrics.csv` of a run directory: the column index of each header name, and the rows split
/// at commas (every row as wide as the header).
pub fn metrics_table(dir: &Path) -> (std::collections::HashMap<String, usize>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(dir.join("metrics.csv")).expect("metrics.csv");
    let header = text.lines().next().expect("a header").split(',');
    let columns = header.enumerate().map(|(k, h)| (h.to_owned(), k)).collect();
    (columns, csv_rows(&dir.join("metrics.csv")))
}

/// The short forming scenario (1.5 s, 16 frames).
pub fn short() -> String {
    format!("{ROOT}/tests/data/form.ron")
}

/// `hagfish run SCENARIO --quiet --out DIR` with `extra` arguments.
pub fn run_into(scenario: &str, dir: &Path, extra: &[&str]) -> std::process::Output {
    let dir = dir.to_string_lossy();
    let mut args = vec!["run", scenario, "--quiet", "--out", &dir];
    args.extend_from_slice(extra);
    run_hagfish(args)
}

/// Every entry under `dir` (recursively, hidden ones and the lock file included): files with
/// their bytes, directories with none, sorted by path.
pub fn everything(dir: &Path) -> Vec<(PathBuf, Option<Vec<u8>>)> {
    let mut entries = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(next) = pending.pop() {
        for entry in std::fs::read_dir(&next).expect("readable") {
            let path = entry.expect("an entry").path();
            if path.is_dir() {
                pending.push(path.clone());
                entries.push((path, None));
            } else {
                let bytes = std::fs::read(&path).expect("readable");
                entries.push((path, Some(bytes)));
            }
        }
    }
    entries.sort();
    entries
}

/// Number of lines of a file (0 if it does not exist yet).
pub fn line_count(path: &Path) -> usize {
    std::fs::read_to_string(path).map_or(0, |t| t.lines().count())
}

/// Waits until the run in `dir` has recorded `frames` frames after frame 0 (at most 120 s).
pub fn wait_for_frames(dir: &Path, frames: usize) {
    let started = std::time::Instant::now();
    while line_count(&dir.join("metrics.csv")) < 1 + frames {
        assert!(started.elapsed() < std::time::Duration::from_secs(120), "no frames after 120 s");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
}

/// Asserts that `output` is of a run stopped by SIGTERM (exit 130, the message) whose
/// directory `dir` says `interrupted`; returns its frames.
pub fn stopped_by_sigterm(output: &Output, dir: &Path) -> u64 {
    let (code, stderr) = code_and_stderr(output);
    assert_eq!(code, Some(130), "{stderr}");
    assert!(stderr.contains("interrupted by a signal after"), "{stderr}");
    let stopped = manifest(dir);
    assert_eq!(stopped["status"], "interrupted");
    stopped["frames"].as_u64().expect("frames")
}
