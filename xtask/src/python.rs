//! The Python step of `cargo xtask test`: a virtual environment with the package `hagfish`
//! built from this checkout (`crates/python`, maturin) and its tests run by pytest.
//!
//! The environment lives in `<target directory>/python-venv` (made with `python3 -m venv` on
//! first use, kept between runs); `pip` installs maturin, NumPy, pandas, pytest, Dask,
//! dask-jobqueue, matplotlib and SALib from PyPI (the `test` extra of
//! `crates/python/pyproject.toml`; nothing is downloaded again once they are there), then
//! builds the package from the checkout without build isolation and reinstalls it (with its
//! `hagfish` command in the environment's `bin`). The tests get the command-line program
//! Cargo built in `HAGFISH_BIN`, to compare runs with it.

use std::path::{Path, PathBuf};
use std::process::Command;

/// What the package's tests need besides the package: its dependencies and its `test` extra
/// (`crates/python/pyproject.toml`; dask-jobqueue for the Slurm job-script test, matplotlib
/// and SALib for the example study in `examples/`).
const TEST_REQUIREMENTS: [&str; 8] = [
    "maturin>=1.9,<2",
    "numpy>=1.22",
    "pandas>=1.5",
    "pytest>=7",
    "dask[distributed]>=2023.1",
    "dask-jobqueue>=0.8",
    "matplotlib>=3.5",
    "SALib>=1.4",
];

/// The target directory Cargo builds into (`CARGO_TARGET_DIR`, else `<root>/target`).
pub fn target_directory(root: &Path) -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root.join("target"), PathBuf::from)
}

/// Makes (or reuses) the environment, installs the package from `root` and runs its tests
/// with the program `hagfish`; `Err` says which command failed.
pub fn test(root: &Path, hagfish: &Path) -> Result<(), String> {
    let venv = target_directory(root).join("python-venv");
    let python = venv.join("bin").join("python");
    if !python.is_file() {
        let interpreter = std::env::var("HAGFISH_PYTHON").unwrap_or_else(|_| "python3".into());
        eprintln!("xtask test: creating {} with {interpreter}", venv.display());
        run(Command::new(&interpreter).args(["-m", "venv"]).arg(&venv), "python3 -m venv")
            .map_err(|e| {
                format!(
                    "{e}; Python ≥ 3.9 with the venv module is needed (Debian: apt-get install \
                     python3-venv), or set HAGFISH_PYTHON to such an interpreter"
                )
            })?;
    }
    // maturin, run by pip without build isolation, is found on PATH.
    let bin = venv.join("bin");
    let path = std::env::var_os("PATH").unwrap_or_default();
    let path = std::env::join_paths(std::iter::once(bin).chain(std::env::split_paths(&path)))
        .map_err(|e| format!("cannot put the environment on PATH: {e}"))?;
    let pip = |arguments: &[&str]| {
        let mut command = Command::new(&python);
        command.env("PATH", &path);
        command.args(["-m", "pip", "install", "--quiet", "--disable-pip-version-check"]);
        command.args(arguments);
        command
    };
    eprintln!("xtask test: pip install the test requirements into {}", venv.display());
    run(&mut pip(&TEST_REQUIREMENTS), "pip install the test requirements")?;
    eprintln!("xtask test: pip install ./crates/python (maturin, release build)");
    let package = root.join("crates").join("python");
    let mut install = pip(&["--no-build-isolation", "--force-reinstall", "--no-deps"]);
    install.arg(&package).env("CARGO_TARGET_DIR", target_directory(root));
    run(&mut install, "pip install ./crates/python")?;
    eprintln!("xtask test: pytest crates/python/tests");
    let mut pytest = Command::new(&python);
    pytest.args(["-m", "pytest", "-q"]).arg(package.join("tests")).current_dir(root);
    run(pytest.env("HAGFISH_BIN", hagfish), "pytest crates/python/tests")
}

/// Runs `command`; `Err` names it (`what`) with its exit status.
fn run(command: &mut Command, what: &str) -> Result<(), String> {
    let status = command.status().map_err(|e| format!("could not start {what}: {e}"))?;
    if status.success() { Ok(()) } else { Err(format!("{what} failed ({status})")) }
}
