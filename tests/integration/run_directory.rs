//! The run directory is the program's alone while it runs and holds only what it wrote:
//! a second process is refused (naming the holder) and a killed one's lock is taken over;
//! a user's files beside the outputs, in `vtk/` included, survive; symbolic links are
//! replaced, never written through; a completed run is replaced only with `--overwrite`,
//! and kept whole if the new run cannot start; a resume refuses an edited body file or
//! checkpoint.

use std::fs::OpenOptions;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use crate::common::{
    ROOT, code_and_stderr, everything, fresh_dir, hagfish, manifest, run_hagfish, run_into, short,
};

/// Every file under `dir` (recursively, the lock file left out) with its bytes, sorted.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let files = everything(dir).into_iter().filter(|(path, _)| !path.ends_with(".hagfish.lock"));
    files.filter_map(|(path, bytes)| Some((path, bytes?))).collect()
}

#[test]
fn a_second_process_is_refused_and_a_killed_ones_lock_is_taken_over() {
    let dir = fresh_dir("run_dir_lock");
    let scenario = format!("{ROOT}/data/scenarios/form.ron");
    let mut first = hagfish(["run", &scenario, "--quiet", "--out", &dir.to_string_lossy()])
        .stdout(std::process::Stdio::null())
        .spawn()
        .expect("hagfish starts");
    let pid = format!("pid {}", first.id());
    let started = Instant::now();
    while !std::fs::read_to_string(dir.join(".hagfish.lock")).unwrap_or_default().contains(&pid) {
        assert!(started.elapsed() < Duration::from_secs(60), "no lock after 60 s");
        std::thread::sleep(Duration::from_millis(2));
    }
    let second = run_into(&scenario, &dir, &["--overwrite"]);
    let resumed = run_hagfish(["run", "--resume", &dir.to_string_lossy(), "--quiet"]);
    // Killed before its first frame's checkpoint, the run would leave nothing to resume (the
    // lock is taken before frame 0 is written: on a loaded machine CI once killed it there).
    while !dir.join("checkpoint.ron").exists() {
        assert!(started.elapsed() < Duration::from_secs(60), "no checkpoint after 60 s");
        std::thread::sleep(Duration::from_millis(2));
    }
    first.kill().expect("SIGKILL");
    first.wait().expect("reaped");
    for output in [second, resumed] {
        let (code, stderr) = code_and_stderr(&output);
        assert_eq!(code, Some(2), "{stderr}");
        assert!(stderr.contains("in use by another hagfish process (pid"), "{stderr}");
        assert!(stderr.contains(&pid), "the message names the holder: {stderr}");
    }
    // The killed run left its lock file; the kernel released the lock with the process.
    let output = run_hagfish(["run", "--resume", &dir.to_string_lossy(), "--quiet"]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    assert_eq!(manifest(&dir)["status"], "completed");
}

#[test]
fn a_users_files_survive_a_run_and_its_replacement() {
    let dir = fresh_dir("run_dir_user_files");
    let mine =
        [dir.join("notes.txt"), dir.join("vtk/mine.vtk"), dir.join("vtk/sub/frame_0001.vtk")];
    for (k, path) in mine.iter().enumerate() {
        std::fs::create_dir_all(path.parent().expect("a parent")).expect("mkdir");
        std::fs::write(path, format!("the user's file {k}")).expect("write");
    }
    assert!(run_into(&short(), &dir, &[]).status.success());
    assert!(dir.join("vtk/frame_0015.vtk").exists(), "the run's own frames are written");
    let output = run_into(&short(), &dir, &["--overwrite", "--set", "duration_s=0.5"]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    assert!(!dir.join("vtk/frame_0015.vtk").exists(), "a frame of the longer run lingers");
    for (k, path) in mine.iter().enumerate() {
        let text = std::fs::read_to_string(path).expect("the user's file is still there");
        assert_eq!(text, format!("the user's file {k}"));
    }
}

#[test]
fn symbolic_links_are_replaced_not_written_through() {
    let dir = fresh_dir("run_dir_symlinks");
    let outside = dir.join("outside.csv");
    std::fs::write(&outside, "precious").expect("write");
    let out = dir.join("out");
    std::fs::create_dir_all(out.join("plots")).expect("mkdir");
    for name in ["metrics.csv", "q.npy", "report.html", "plots/contacts.png"] {
        std::os::unix::fs::symlink(&outside, out.join(name)).expect("symlink");
    }
    assert!(run_into(&short(), &out, &[]).status.success());
    assert_eq!(std::fs::read_to_string(&outside).expect("read"), "precious");
    for name in ["metrics.csv", "q.npy", "report.html", "plots/contacts.png"] {
        let kind = std::fs::symlink_metadata(out.join(name)).expect("exists").file_type();
        assert!(kind.is_file(), "{name} is the run's own file now");
    }
}

#[test]
fn a_completed_run_is_replaced_only_when_asked_and_kept_if_the_new_one_cannot_start() {
    let dir = fresh_dir("run_dir_overwrite");
    assert!(run_into(&short(), &dir, &[]).status.success());
    let before = snapshot(&dir);

    let refused = run_into(&short(), &dir, &[]);
    let (code, stderr) = code_and_stderr(&refused);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("holds a run (status completed)"), "{stderr}");
    assert!(stderr.contains("--overwrite"), "{stderr}");
    assert_eq!(snapshot(&dir), before, "a refused run changed the directory");

    // The new run fails after its output files are made: its scenario.ron cannot be
    // written (a directory is in the way of the temporary file).
    let blocker = dir.join("scenario.ron.partial");
    std::fs::create_dir_all(blocker.join("in the way")).expect("mkdir");
    let failed = run_into(&short(), &dir, &["--overwrite", "--set", "duration_s=0.5"]);
    assert_eq!(code_and_stderr(&failed).0, Some(2), "{}", code_and_stderr(&failed).1);
    std::fs::remove_dir_all(&blocker).expect("rmdir");
    assert_eq!(snapshot(&dir), before, "the failed re-run changed the completed run");
    assert_eq!(manifest(&dir)["status"], "completed");

    let replaced = run_into(&short(), &dir, &["--overwrite", "--set", "duration_s=0.5"]);
    assert!(replaced.status.success(), "{}", code_and_stderr(&replaced).1);
    assert_eq!(manifest(&dir)["frames"], 6);
    assert!(!dir.join(".hagfish-previous").exists());
}

/// A run of the short scenario with its own copy of the body file, stopped after frame 5.
fn stopped_run(name: &str) -> (PathBuf, PathBuf) {
    let dir = fresh_dir(name);
    let body = dir.join("body.ron");
    std::fs::copy(format!("{ROOT}/data/hagfish/es103.ron"), &body).expect("copy the body");
    let out = dir.join("out");
    let body_arg = body.to_string_lossy().into_owned();
    let output = run_into(&short(), &out, &["--body", &body_arg, "--stop-after-frames", "5"]);
    assert!(output.status.success(), "{}", code_and_stderr(&output).1);
    assert_eq!(manifest(&out)["status"], "interrupted");
    (out, body)
}

#[test]
fn a_resume_refuses_an_edited_body_file() {
    let (out, body) = stopped_run("run_dir_body_edit");
    let mut file = OpenOptions::new().append(true).open(&body).expect("open");
    writeln!(file, "// an edit").expect("append");
    let output = run_hagfish(["run", "--resume", &out.to_string_lossy(), "--quiet"]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("the body file changed since the run's checkpoint"), "{stderr}");
    assert!(stderr.contains("body.ron"), "{stderr}");
}

#[test]
fn a_resume_refuses_an_edited_checkpoint() {
    let (out, _) = stopped_run("run_dir_checkpoint_edit");
    let path = out.join("checkpoint.ron");
    let text = std::fs::read_to_string(&path).expect("checkpoint.ron");
    let at = text.find("q: \"").expect("q") + 4;
    let digit = if text.as_bytes()[at] == b'3' { "4" } else { "3" };
    std::fs::write(&path, format!("{}{digit}{}", &text[..at], &text[at + 1..])).expect("write");
    let output = run_hagfish(["run", "--resume", &out.to_string_lossy(), "--quiet"]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("checksum mismatch"), "{stderr}");
    // The checksum the edited content would need is not shown (it could be pasted in).
    let edited = std::fs::read(&path).expect("checkpoint.ron");
    let rest =
        edited.iter().position(|&b| b == b'\n').map_or(&edited[..], |end| &edited[end + 1..]);
    let needed = format!("{:016x}", hagfish_sim::fnv1a64(rest));
    assert!(!stderr.contains(&needed), "the message shows the checksum to paste: {stderr}");
}

#[test]
fn a_resume_refuses_an_array_changed_in_place_naming_the_rows_not_the_hash() {
    let (out, _) = stopped_run("run_dir_npy_edit");
    let path = out.join("q.npy");
    let mut bytes = std::fs::read(&path).expect("q.npy");
    let length = bytes.len();
    bytes[128 + 8 * 3] ^= 1; // one bit of a value of row 0, same length
    std::fs::write(&path, &bytes).expect("write");
    let output = run_hagfish(["run", "--resume", &out.to_string_lossy(), "--quiet"]);
    let (code, stderr) = code_and_stderr(&output);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("q.npy: cannot resume: its first 6 rows are not those"), "{stderr}");
    let checkpoint = std::fs::read_to_string(out.join("checkpoint.ron")).expect("checkpoint");
    let recorded = checkpoint.split(|c: char| !c.is_ascii_hexdigit()).filter(|w| w.len() == 16);
    for hash in recorded {
        assert!(!stderr.contains(hash), "the message shows a recorded hash {hash}: {stderr}");
    }
    assert_eq!(std::fs::read(&path).expect("q.npy"), bytes, "the refused resume cut q.npy");
    assert_eq!(bytes.len(), length);
    assert_eq!(manifest(&out)["status"], "interrupted");
}
