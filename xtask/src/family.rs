//! `cargo xtask family`: runs a knot scenario (tie → tighten → slide) on the family of bodies
//! and time steps of `hagfish_bench_support::family` and prints its knot table, as in
//! `docs/physics.md`: when tied, how long held, where the core was, the slide's travel,
//! speed and length change, the deepest penetration. The runs use the release `hagfish`
//! binary (built first) and their directories stay under `<target>/family/` for a closer
//! look; several run at once.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;

use hagfish_bench_support::{KnotRun, TABLE_HEADER, Variant, family};

use crate::python::target_directory;

/// What to tabulate.
pub struct Request<'a> {
    /// The scenario file.
    pub scenario: &'a Path,
    /// The knot the scenario ties (`3_1` is held only with the member's handedness).
    pub knot: &'a str,
    /// `--set PATH=VALUE` overrides for every run.
    pub sets: &'a [String],
    /// Runs at a time.
    pub jobs: usize,
    /// Only the members of these names (all when empty).
    pub only: &'a [String],
}

/// Builds `hagfish`, runs every member and prints the table (a row for each member, in the
/// family's order; a run that fails says how in its row).
pub fn run(root: &Path, request: &Request<'_>) -> Result<(), String> {
    let status = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()))
        .args(["build", "--release", "--bin", "hagfish"])
        .current_dir(root)
        .status()
        .map_err(|e| format!("could not start cargo build: {e}"))?;
    if !status.success() {
        return Err(format!("cargo build --release --bin hagfish failed ({status})"));
    }
    let target = target_directory(root);
    let hagfish = target.join("release").join("hagfish");
    let stem = request.scenario.file_stem().map_or("scenario".into(), |s| s.to_string_lossy());
    let work = target.join("family").join(stem.as_ref());
    std::fs::create_dir_all(&work).map_err(|e| format!("{}: {e}", work.display()))?;
    let es103 = std::fs::read_to_string(root.join("data/hagfish/es103.ron"))
        .map_err(|e| format!("data/hagfish/es103.ron: {e}"))?;
    // The left-handed member is the trefoil's mirror image: no other knot has one.
    let members: Vec<Variant> = family()
        .into_iter()
        .filter(|v| v.right_handed || request.knot == "3_1")
        .filter(|v| request.only.is_empty() || request.only.iter().any(|name| name == v.name))
        .collect();
    if let Some(unknown) = request.only.iter().find(|n| !members.iter().any(|v| v.name == *n)) {
        let names: Vec<&str> = family().iter().map(|v| v.name).collect();
        return Err(format!("no member {unknown} in the family ({})", names.join(", ")));
    }
    let queue = Mutex::new(members.iter().enumerate());
    let rows = Mutex::new(vec![String::new(); members.len()]);
    std::thread::scope(|scope| {
        for _ in 0..request.jobs.max(1) {
            scope.spawn(|| {
                let next = || queue.lock().map(|mut q| q.next()).ok().flatten();
                while let Some((index, variant)) = next() {
                    let row = member_row(&hagfish, &work, &es103, variant, request);
                    eprintln!("{row}");
                    if let Ok(mut rows) = rows.lock() {
                        rows[index] = row;
                    }
                }
            });
        }
    });
    let rows = rows.into_inner().map_err(|_| "a run panicked")?;
    println!(
        "`cargo xtask family --scenario {} --knot {}{}{}` ({} members):\n\n{TABLE_HEADER}",
        request.scenario.display(),
        request.knot,
        request.sets.iter().map(|s| format!(" --set {s}")).collect::<String>(),
        request.only.iter().map(|s| format!(" --only {s}")).collect::<String>(),
        rows.len()
    );
    for row in rows {
        println!("{row}");
    }
    Ok(())
}

/// The table row of `variant`: its run measured, or what stopped it.
fn member_row(
    hagfish: &Path,
    work: &Path,
    es103: &str,
    variant: &Variant,
    request: &Request<'_>,
) -> String {
    let failed = |why: &str| format!("| {} | — ({why}) | | | | | | | | |", variant.name);
    let body = match variant.body(es103) {
        Ok(body) => body,
        Err(e) => return failed(&e),
    };
    let body_path: PathBuf = work.join(format!("{}.ron", variant.name));
    if let Err(e) = std::fs::write(&body_path, body) {
        return failed(&format!("{}: {e}", body_path.display()));
    }
    let out = work.join(variant.name);
    let mut command = Command::new(hagfish);
    command.arg("run").arg(request.scenario).arg("--body").arg(&body_path);
    command.arg("--out").arg(&out).args(["--quiet", "--overwrite"]);
    for set in variant.sets.iter().copied().chain(request.sets.iter().map(String::as_str)) {
        command.args(["--set", set]);
    }
    let output = match command.output() {
        Ok(output) => output,
        Err(e) => return failed(&format!("could not start hagfish: {e}")),
    };
    if !output.status.success() {
        let stderr = String::from_utf8_lossy(&output.stderr);
        let last = stderr.lines().rfind(|l| l.starts_with("error")).unwrap_or("");
        return failed(&format!("exit {}: {last}", output.status.code().unwrap_or(-1)));
    }
    let sign = (request.knot == "3_1").then_some(if variant.right_handed { 1.0 } else { -1.0 });
    match KnotRun::read(&out) {
        Ok(run) => run.table_row(variant.name, request.knot, sign),
        Err(e) => failed(&e),
    }
}
