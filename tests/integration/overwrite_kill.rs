//! `--overwrite` under SIGKILL (issue 39, item 1): killed at any instant, the directory holds
//! either the earlier run (as it was, or put back by `hagfish recover DIR`) or the new run
//! with a checkpoint, which `hagfish run --resume DIR` completes.

use std::path::{Path, PathBuf};
use std::time::Duration;

use crate::common::{
    code_and_stderr, everything, fresh_dir, hagfish, manifest, run_hagfish, run_into, short,
};

/// Copies the directory tree `from` to `to` (files and directories only).
fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("mkdir");
    for entry in std::fs::read_dir(from).expect("readable") {
        let entry = entry.expect("an entry");
        let target = to.join(entry.file_name());
        if entry.file_type().expect("a type").is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).expect("copy");
        }
    }
}

/// [`everything`] under `dir` but the lock file (which names the last process that held it),
/// relative to `dir`.
fn run_files(dir: &Path) -> Vec<(PathBuf, Option<Vec<u8>>)> {
    everything(dir)
        .into_iter()
        .filter(|(path, _)| !path.ends_with(".hagfish.lock"))
        .map(|(path, bytes)| (path.strip_prefix(dir).expect("under dir").to_path_buf(), bytes))
        .collect()
}

/// What a kill left, once recovered or resumed.
#[derive(Debug, Default)]
struct Tally {
    untouched: usize,
    recovered: usize,
    resumed: usize,
    new_complete: usize,
}

#[test]
fn an_overwrite_killed_at_any_instant_leaves_the_earlier_run_or_a_resumable_new_one() {
    let root = fresh_dir("overwrite_kill");
    let template = root.join("template");
    assert!(run_into(&short(), &template, &[]).status.success());
    let earlier = run_files(&template);
    let mut tally = Tally::default();
    for k in 0..36u64 {
        let dir = root.join(format!("run{k}"));
        copy_tree(&template, &dir);
        let dir_arg = dir.to_string_lossy().into_owned();
        let args = ["run", &short(), "--quiet", "--out", &dir_arg, "--overwrite"];
        let mut child = hagfish(args.iter().chain(&["--set", "duration_s=0.5"]))
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .expect("hagfish starts");
        // 0 to ≈ 60 ms, densest early (set-aside and first frame come within a few ms).
        let delay_us = k * k * 47;
        std::thread::sleep(Duration::from_micros(delay_us));
        child.kill().expect("SIGKILL");
        child.wait().expect("reaped");
        let context = format!("killed after {delay_us} µs");
        if dir.join(".hagfish-previous").exists() {
            let output = run_hagfish(["recover", &dir_arg]);
            assert!(output.status.success(), "{context}: {}", code_and_stderr(&output).1);
            assert!(run_files(&dir) == earlier, "{context}: the earlier run is not back");
            tally.recovered += 1;
        } else if run_files(&dir) == earlier {
            tally.untouched += 1;
        } else if manifest(&dir)["status"] == "completed" {
            assert_eq!(manifest(&dir)["frames"], 6, "{context}");
            tally.new_complete += 1;
        } else {
            assert!(dir.join("checkpoint.ron").exists(), "{context}: a new run without checkpoint");
            let output = run_hagfish(["run", "--resume", &dir_arg, "--quiet"]);
            assert!(output.status.success(), "{context}: {}", code_and_stderr(&output).1);
            assert_eq!(manifest(&dir)["status"], "completed", "{context}");
            assert_eq!(manifest(&dir)["frames"], 6, "{context}");
            assert!(!dir.join(".hagfish-discarded").exists(), "{context}");
            tally.resumed += 1;
        }
        std::fs::remove_dir_all(&dir).expect("rm");
    }
    eprintln!("{tally:?}");
    assert_eq!(tally.untouched + tally.recovered + tally.resumed + tally.new_complete, 36);
}

#[test]
fn recover_says_when_there_is_nothing_to_put_back() {
    let root = fresh_dir("overwrite_recover_nothing");
    let dir = root.join("run");
    assert!(run_into(&short(), &dir, &["--stop-after-frames", "2"]).status.success());
    let before = run_files(&dir);
    let output = run_hagfish(["recover", &dir.to_string_lossy()]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    assert!(String::from_utf8_lossy(&output.stdout).contains("nothing set aside"));
    assert!(run_files(&dir) == before);
}
