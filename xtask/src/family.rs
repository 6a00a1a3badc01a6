//! `cargo xtask family`: runs a knot scenario on the family of bodies and time steps of
//! `hagfish_bench_support::family` and prints its table, as in `docs/physics.md`:
//! - `--measure slide` (tie → tighten → slide): when tied, how long held, where the core was,
//!   the slide's travel, speed and length change, the deepest penetration;
//! - `--measure loosen-tighten` (tie → loosen → tighten): the core's length change over the
//!   loosen and the tighten phase, each beside its control run (the same scenario with that
//!   phase's head and tail targets at zero), and whether both effects are the targets' doing
//!   (≥ 25 % and ≥ 20 points past the control, the knot held, penetration below 2 %);
//! - `--measure modes` (tie → tighten → slide): the modes of the slide's force field and each
//!   member's basis against ES103's (`family_modes.rs`).
//!
//! The runs use the release `hagfish` binary (built first) and their directories stay under
//! `<target>/family/` for a closer look; several run at once.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Mutex;

use hagfish_bench_support::{Variant, family};
use hagfish_control::Phase;
use hagfish_report::{KnotRun, LoosenTighten, SlideBounds, TABLE_HEADER, signed_percent};
use hagfish_scenario::LoadedScenario;

use crate::family_cases::{Case, cases};
use crate::python::target_directory;
use crate::test_all::cargo;

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
    /// What to measure.
    pub measure: Measure,
    /// Runs per member (`family_cases.rs`): the member as written and `rounding − 1`
    /// rounding perturbations of its time step.
    pub rounding: usize,
}

/// What a table measures of each member.
#[derive(Clone, Debug, PartialEq)]
pub enum Measure {
    /// The slide of a tie → tighten → slide scenario ([`KnotRun`]).
    Slide,
    /// The loosen and tighten of a tie → loosen → tighten scenario ([`LoosenTighten`]),
    /// each against its control run.
    LoosenTighten,
    /// The modes of a phase's force field and the basis against ES103's
    /// ([`crate::family_modes`]).
    Modes(crate::family_modes::ModesMeasure),
    /// The slide of a knot tied around the scenario's first still cylinder: its turns about
    /// it and its travel along it beside the slide's measures ([`crate::family_cylinder`]).
    Cylinder,
}

/// The header of the loosen/tighten table.
const LOOSEN_TIGHTEN_HEADER: &str = "| variant | loosen (control) | tighten (control) | both ≥ 25 % \
     and ≥ 20 points past the control |\n|---|---|---|---|";

/// Builds `hagfish`, runs every member and prints the table (a row for each member, in the
/// family's order; a run that fails says how in its row).
pub fn run(root: &Path, request: &Request<'_>) -> Result<(), String> {
    let status = Command::new(cargo())
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
    // Read once here, so that a scenario that cannot run is said once, not by every member.
    let loaded = LoadedScenario::load(request.scenario).map_err(|e| e.to_string())?;
    let controls = match request.measure {
        Measure::Slide | Measure::Modes(_) | Measure::Cylinder => None,
        Measure::LoosenTighten => Some(control_phases(&loaded, request.scenario)?),
    };
    let runner = Runner { hagfish: &hagfish, work: &work, es103: &es103, request };
    let (measure, header) = match &request.measure {
        Measure::Slide => ("slide", TABLE_HEADER),
        Measure::LoosenTighten => ("loosen-tighten", LOOSEN_TIGHTEN_HEADER),
        Measure::Modes(modes) => {
            print_command(request, members.len(), "modes");
            return crate::family_modes::run(&runner, &members, modes, loaded.scenario.time_step_s);
        }
        Measure::Cylinder => {
            let axis = crate::family_cylinder::cylinder_axis(&loaded)?;
            print_command(request, members.len(), "cylinder");
            let step = loaded.scenario.time_step_s;
            return crate::family_cylinder::run(&runner, &members, axis, step);
        }
    };
    if let Some(controls) = controls {
        let rows = in_parallel(&members, request.jobs, |variant| {
            let row = runner.loosen_tighten_row(variant, controls);
            eprintln!("{row}");
            row
        })?;
        print_command(request, rows.len(), measure);
        println!("{header}");
        rows.iter().for_each(|row| println!("{row}"));
        return Ok(());
    }
    print_command(request, members.len(), measure);
    let passing = format!("pass {}", SlideBounds::for_knot(request.knot));
    let step = loaded.scenario.time_step_s;
    run_judged(&runner, &members, header, &passing, |case| runner.slide_row(case, step))
}

/// Runs `row` on every case of `members` (each member and its rounding perturbations,
/// `family_cases.rs`), `jobs` at a time, each row echoed to stderr as it comes; prints the
/// table under `header` and below it how many runs `passing` (what they do to count: "pass
/// the trefoil's slide bounds (…)"), naming what each other run missed. `row` gives a case's
/// table row and, when it misses, how.
pub fn run_judged(
    runner: &Runner<'_>,
    members: &[Variant],
    header: &str,
    passing: &str,
    row: impl Fn(&Case<'_>) -> (String, Option<String>) + Sync,
) -> Result<(), String> {
    let bodies: Vec<Result<PathBuf, String>> = members.iter().map(|v| runner.body(v)).collect();
    let cases = cases(members, &bodies, runner.request.rounding);
    let rows = in_parallel(&cases, runner.request.jobs, |case| {
        let row = row(case);
        eprintln!("{}", row.0);
        row
    })?;
    println!("{header}");
    rows.iter().for_each(|(row, _)| println!("{row}"));
    let failed: Vec<(String, &String)> = cases
        .iter()
        .zip(&rows)
        .filter_map(|(c, (_, f))| f.as_ref().map(|f| (c.label(), f)))
        .collect();
    println!(
        "\n{} of {} runs {passing}{}",
        rows.len() - failed.len(),
        rows.len(),
        if failed.is_empty() { "." } else { "; the others:" }
    );
    failed.iter().for_each(|(label, why)| println!("- {label}: {why}"));
    Ok(())
}

/// Prints the command that makes the table and the number of members.
fn print_command(request: &Request<'_>, members: usize, measure: &str) {
    let mut extra = match &request.measure {
        Measure::Modes(modes) => modes.arguments(),
        _ => String::new(),
    };
    if request.rounding > 1 {
        extra += &format!(" --rounding {}", request.rounding);
    }
    println!(
        "`cargo xtask family --scenario {} --knot {} --measure {measure}{extra}{}{}` ({members} \
         member{}):\n",
        request.scenario.display(),
        request.knot,
        request.sets.iter().map(|s| format!(" --set {}", shell_word(s))).collect::<String>(),
        request.only.iter().map(|s| format!(" --only {s}")).collect::<String>(),
        if members == 1 { "" } else { "s" },
    );
}

/// `text` as one shell word: in double quotes when it holds a space, a parenthesis or a
/// bracket (`friction=Some((coefficient: 0.3))`), so that a printed command can be pasted.
pub fn shell_word(text: &str) -> String {
    if text.contains([' ', '(', ')', '[', ']']) { format!("\"{text}\"") } else { text.into() }
}

/// `values` as a command line's comma-separated list (`0.3,0.6,0.9`).
pub fn comma_list<T: ToString>(values: &[T]) -> String {
    values.iter().map(T::to_string).collect::<Vec<_>>().join(",")
}

/// `work` applied to each of `items` by `jobs` threads at a time; the results in the items'
/// order.
pub fn in_parallel<T: Sync, R: Send>(
    items: &[T],
    jobs: usize,
    work: impl Fn(&T) -> R + Sync,
) -> Result<Vec<R>, String> {
    let queue = Mutex::new(items.iter().enumerate());
    let results = Mutex::new((0..items.len()).map(|_| None).collect::<Vec<Option<R>>>());
    std::thread::scope(|scope| {
        for _ in 0..jobs.max(1) {
            scope.spawn(|| {
                let next = || queue.lock().map(|mut q| q.next()).ok().flatten();
                while let Some((index, item)) = next() {
                    let result = work(item);
                    if let Ok(mut results) = results.lock() {
                        results[index] = Some(result);
                    }
                }
            });
        }
    });
    let results = results.into_inner().map_err(|_| "a run panicked")?;
    results.into_iter().map(|r| r.ok_or_else(|| "a run panicked".into())).collect()
}

/// The indices of the phases named `loosen` and `tighten` in `loaded`, read from `scenario`.
fn control_phases(loaded: &LoadedScenario, scenario: &Path) -> Result<[usize; 2], String> {
    let index = |name: &str| {
        loaded
            .scenario
            .phases
            .iter()
            .position(|p| matches!(p, Phase::Thigmotaxis(t) if t.name == name))
            .ok_or(format!("{} has no thigmotaxis phase named {name}", scenario.display()))
    };
    Ok([index("loosen")?, index("tighten")?])
}

/// Runs members of the family.
pub struct Runner<'a> {
    hagfish: &'a Path,
    work: &'a Path,
    es103: &'a str,
    /// What was asked.
    pub request: &'a Request<'a>,
}

impl Runner<'_> {
    /// Writes `variant`'s body file into `<work>/<name>.ron` and returns its path.
    pub fn body(&self, variant: &Variant) -> Result<PathBuf, String> {
        let path = self.work.join(format!("{}.ron", variant.name));
        std::fs::write(&path, variant.body(self.es103)?)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(path)
    }

    /// Runs `variant` on its body file `body` with the `extra` overrides into
    /// `<work>/<name><suffix>`; the directory, or what stopped the run (its exit code and
    /// error line).
    pub fn run(
        &self,
        variant: &Variant,
        body: &Path,
        suffix: &str,
        extra: &[String],
    ) -> Result<PathBuf, String> {
        let out = self.work.join(format!("{}{suffix}", variant.name));
        let mut command = Command::new(self.hagfish);
        command.arg("run").arg(self.request.scenario).arg("--body").arg(body);
        command.arg("--out").arg(&out).args(["--quiet", "--overwrite"]);
        let sets = variant.sets.iter().copied().chain(self.request.sets.iter().map(String::as_str));
        for set in sets.chain(extra.iter().map(String::as_str)) {
            command.args(["--set", set]);
        }
        let output = command.output().map_err(|e| format!("could not start hagfish: {e}"))?;
        if output.status.success() {
            return Ok(out);
        }
        let stderr = String::from_utf8_lossy(&output.stderr);
        let last = stderr.lines().rfind(|l| l.starts_with("error")).unwrap_or("");
        Err(format!("exit {}: {last}", output.status.code().unwrap_or(-1)))
    }

    /// The slide table's row of `case` and, when it misses its knot's bounds
    /// ([`SlideBounds::for_knot`]), how;
    /// `scenario_step` as in [`Case::run`].
    fn slide_row(&self, case: &Case<'_>, scenario_step: f64) -> (String, Option<String>) {
        let knot = self.request.knot;
        let sign = (knot == "3_1").then_some(if case.variant.right_handed { 1.0 } else { -1.0 });
        let measured = case
            .run(self, scenario_step, &[])
            .and_then(|out| KnotRun::read(&out).map_err(|e| e.to_string()));
        match measured {
            Ok(run) => {
                let failures = run.failures(&SlideBounds::for_knot(knot), knot, sign);
                let row = run.table_row(&case.label(), knot, sign);
                (row, (!failures.is_empty()).then(|| failures.join("; ")))
            }
            Err(why) => (format!("| {} | — ({why}) | | | | | | | | | |", case.label()), Some(why)),
        }
    }

    /// The loosen/tighten table's row of `variant`: the run, and a control run for each of
    /// the phases `controls` (loosen, tighten) with that phase's targets at zero.
    fn loosen_tighten_row(&self, variant: &Variant, controls: [usize; 2]) -> String {
        let zero = |phase: usize| {
            ["head", "tail"]
                .map(|end| format!("phases[{phase}].Thigmotaxis.parameters.{end}=(0.0, 0.0)"))
        };
        let body = match self.body(variant) {
            Ok(body) => body,
            Err(why) => return format!("| {} | — ({why}) | | no |", variant.name),
        };
        let measure = |suffix: &str, extra: &[String]| {
            let out = self.run(variant, &body, suffix, extra)?;
            LoosenTighten::read(&out, self.request.knot).map_err(|e| e.to_string())
        };
        let runs = (
            measure("", &[]),
            measure("_loosen_control", &zero(controls[0])),
            measure("_tighten_control", &zero(controls[1])),
        );
        let (run, loosen_control, tighten_control) = match runs {
            (Ok(run), Ok(loosen), Ok(tighten)) => (run, loosen, tighten),
            (Err(why), _, _) => return format!("| {} | — ({why}) | | no |", variant.name),
            (_, Err(why), _) | (_, _, Err(why)) => {
                return format!("| {} | — (a control: {why}) | | no |", variant.name);
            }
        };
        let percent = |change: Option<f64>| signed_percent(change.unwrap_or(f64::NAN));
        let lost = |sizes: &LoosenTighten| {
            sizes
                .lost_in
                .as_ref()
                .map_or(String::new(), |phase| format!(", knot lost in the {phase}"))
        };
        let passed = run.failures(&loosen_control, &tighten_control).is_empty();
        format!(
            "| {} | {} ({}{}) | {} ({}{}) | {}{} |",
            variant.name,
            percent(run.loosen),
            percent(loosen_control.loosen),
            lost(&loosen_control),
            percent(run.tighten),
            percent(tighten_control.tighten),
            lost(&tighten_control),
            if passed { "yes" } else { "no" },
            lost(&run),
        )
    }
}
