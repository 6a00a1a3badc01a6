//! `cargo xtask test`: the project's one test command (README, `.ci/run`). It finds or
//! installs what the tests need, then runs the scenario regression and every test:
//!
//! 1. Chromium for the browser test of `report.html` (`tests/integration/render_command.rs`):
//!    the path in `HAGFISH_CHROMIUM`, else `chromium` (or `chromium-browser`) on `PATH` or in
//!    `/usr/bin`, else Debian's package `chromium` installed with `apt-get` when this process
//!    may (root, or password-less `sudo`). The path found is handed to the tests in
//!    `HAGFISH_CHROMIUM`.
//! 2. `cargo xtask regress --check` (in this process).
//! 3. `cargo test --workspace --release`.
//! 4. The API docs: `cargo doc --no-deps --workspace` with rustdoc's warnings as errors, so
//!    that a broken link in a doc comment fails here rather than on a reader.
//! 5. The Python package: a virtual environment in the target directory, the package built
//!    from `crates/python` and installed there, its pytest suite ([`crate::python`]).
//!
//! Each step says what it does on stderr; the first failure stops the command with a non-zero
//! exit code and a line that names the step.

use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::process::Command;

use crate::{python, regress};

/// The environment variable through which the browser test finds Chromium.
pub const CHROMIUM_VARIABLE: &str = "HAGFISH_CHROMIUM";

/// Debian's package that provides `/usr/bin/chromium`.
const CHROMIUM_PACKAGE: &str = "chromium";

/// Runs the whole test suite from the workspace `root`; `Err` names the step that failed.
pub fn run(root: &Path) -> Result<(), String> {
    let chromium = find_or_install_chromium()?;
    eprintln!("xtask test: Chromium at {}", chromium.display());
    eprintln!("xtask test: scenario regression (cargo xtask regress --check)");
    if !regress::run(root, regress::Mode::Check, &[])? {
        return Err("the scenario regression failed (table above)".into());
    }
    eprintln!("xtask test: cargo test --workspace --release");
    let status = Command::new(cargo())
        .args(["test", "--workspace", "--release"])
        .current_dir(root)
        .env(CHROMIUM_VARIABLE, &chromium)
        .status()
        .map_err(|e| format!("could not start cargo test: {e}"))?;
    if !status.success() {
        return Err(format!("cargo test --workspace --release failed ({status})"));
    }
    eprintln!("xtask test: cargo doc --no-deps --workspace (rustdoc warnings are errors)");
    let status = Command::new(cargo())
        .args(["doc", "--no-deps", "--workspace"])
        .current_dir(root)
        .env("RUSTDOCFLAGS", "-D warnings")
        .status()
        .map_err(|e| format!("could not start cargo doc: {e}"))?;
    if !status.success() {
        return Err(format!("cargo doc --no-deps --workspace failed ({status})"));
    }
    let hagfish = python::target_directory(root).join("release").join("hagfish");
    python::test(root, &hagfish)
}

/// The `cargo` that runs this task (Cargo sets `CARGO` for the programs it runs).
pub fn cargo() -> OsString {
    std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into())
}

/// Chromium's path: found (see the module doc) or installed from Debian's packages.
fn find_or_install_chromium() -> Result<PathBuf, String> {
    if let Some(path) = find_chromium()? {
        return Ok(path);
    }
    eprintln!("xtask test: Chromium not found; installing Debian's package `{CHROMIUM_PACKAGE}`");
    let runner = privilege_runner().ok_or_else(|| {
        format!(
            "Chromium is needed by the browser test and was not found: install Debian's \
             `{CHROMIUM_PACKAGE}` (apt-get install -y {CHROMIUM_PACKAGE}) or set \
             {CHROMIUM_VARIABLE} to a Chromium binary; this process may not install it (not \
             root, no password-less sudo)"
        )
    })?;
    apt_get(&runner, &["update"])?;
    apt_get(&runner, &["install", "-y", CHROMIUM_PACKAGE])?;
    find_chromium()?.ok_or_else(|| {
        format!("apt-get installed `{CHROMIUM_PACKAGE}` but no chromium binary was found after it")
    })
}

/// Runs `apt-get ARGUMENTS` behind the privilege `prefix` (empty when root).
fn apt_get(prefix: &[String], arguments: &[&str]) -> Result<(), String> {
    let mut words: Vec<&str> = prefix.iter().map(String::as_str).collect();
    words.push("apt-get");
    words.extend_from_slice(arguments);
    let status = Command::new(words[0])
        .args(&words[1..])
        .env("DEBIAN_FRONTEND", "noninteractive")
        .status()
        .map_err(|e| format!("could not run {}: {e}", words.join(" ")))?;
    if status.success() { Ok(()) } else { Err(format!("{} failed ({status})", words.join(" "))) }
}

/// `HAGFISH_CHROMIUM` if set (an error if it names no file), else the first `chromium` or
/// `chromium-browser` on `PATH` or in `/usr/bin`.
fn find_chromium() -> Result<Option<PathBuf>, String> {
    if let Some(given) = std::env::var_os(CHROMIUM_VARIABLE) {
        let path = PathBuf::from(given);
        return if path.is_file() {
            Ok(Some(path))
        } else {
            Err(format!("{CHROMIUM_VARIABLE}={} is not a file", path.display()))
        };
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    let directories: Vec<PathBuf> =
        std::env::split_paths(&path).chain([PathBuf::from("/usr/bin")]).collect();
    Ok(["chromium", "chromium-browser"]
        .iter()
        .flat_map(|name| directories.iter().map(move |d| d.join(name)))
        .find(|p| p.is_file()))
}

/// How to run `apt-get` with the privileges it needs: directly as root (an empty prefix), or
/// through `sudo -n` when that works without a password; `None` when neither does.
fn privilege_runner() -> Option<Vec<String>> {
    let is_root = Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| o.status.success() && String::from_utf8_lossy(&o.stdout).trim() == "0");
    if is_root {
        return Some(Vec::new());
    }
    let sudo = Command::new("sudo").args(["-n", "true"]).status();
    sudo.is_ok_and(|s| s.success()).then(|| vec!["sudo".to_string(), "-n".to_string()])
}
