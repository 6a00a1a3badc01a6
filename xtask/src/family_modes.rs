//! `cargo xtask family --measure modes [--phase NAME] [--kind K]… [--rounding N]`: runs the
//! scenario on each member (and its rounding perturbations, `family_cases.rs`), decomposes the phase's force field
//! (`hagfish_modes`) and prints two tables per DOF kind:
//! - the modes: energy of modes 1–4, the modes for 90/95/99 %, the travelling-wave fit of
//!   modes 1–2 (k, ω, c = ω/k with their R²) and the knot's speed;
//! - the basis against ES103's (its unperturbed run): the principal angles between the first
//!   4 modes of the member and of ES103, and the energy of the member's field that ES103's
//!   first 2, 4, 8 modes capture, beside what the member's own first 2, 4, 8 modes capture.
//!
//! With `--rounding N` > 1, each member's runs are followed by a row of their spread (min – max).

use std::path::PathBuf;

use hagfish_bench_support::Variant;
use hagfish_modes::{Comparison, Decomposition, KindSelection, RunField};

use crate::family::{Runner, in_parallel};
use crate::family_cases::{Case, cases};

/// The modes whose spans' principal angles are tabulated.
const ANGLE_MODES: usize = 4;

/// The numbers of ES103's modes whose captured energy is tabulated.
const CAPTURE_MODES: [usize; 3] = [2, 4, 8];

/// The member the bases are compared against.
const REFERENCE: &str = "es103";

/// What the modes measure decomposes.
#[derive(Clone, Debug, PartialEq)]
pub struct ModesMeasure {
    /// The phase (`metrics.csv`'s `phase`).
    pub phase: String,
    /// The DOF kinds, one table pair each (one kind: bend-y, bend-z, twist).
    pub kinds: Vec<KindSelection>,
}

impl ModesMeasure {
    /// The command-line arguments that ask for this measure's options.
    pub fn arguments(&self) -> String {
        let kinds: String = self.kinds.iter().map(|k| format!(" --kind {k}")).collect();
        format!(" --phase {}{kinds}", self.phase)
    }
}

/// A table column: its header and the decimals its numbers are printed with.
struct Column(&'static str, usize);

/// The columns of the modes table.
const MODES_COLUMNS: [Column; 17] = [
    Column("frames", 0),
    Column("DOFs", 0),
    Column("e₁ %", 1),
    Column("e₂ %", 1),
    Column("e₃ %", 1),
    Column("e₄ %", 1),
    Column("n 90 %", 0),
    Column("n 95 %", 0),
    Column("n 99 %", 0),
    Column("k rad/cm", 4),
    Column("R² k", 2),
    Column("ω rad/s", 3),
    Column("R² ω", 2),
    Column("c cm/s", 2),
    Column("knot cm/s", 3),
    Column("R² knot", 3),
    Column("c / knot", 2),
];

/// The columns of the basis table.
const BASIS_COLUMNS: [Column; 10] = [
    Column("θ₁ °", 2),
    Column("θ₂ °", 2),
    Column("θ₃ °", 2),
    Column("θ₄ °", 2),
    Column("ES103's 2 %", 1),
    Column("own 2 %", 1),
    Column("ES103's 4 %", 1),
    Column("own 4 %", 1),
    Column("ES103's 8 %", 1),
    Column("own 8 %", 1),
];

/// Runs `members` (each `measure.rounding` times) with `runner` and prints the tables;
/// `scenario_step` is the scenario's time step (s), the base of a member that sets none.
pub fn run(
    runner: &Runner<'_>,
    members: &[Variant],
    measure: &ModesMeasure,
    scenario_step: f64,
) -> Result<(), String> {
    if !members.iter().any(|v| v.name == REFERENCE) {
        return Err(format!("the modes measure compares with {REFERENCE}: include it (--only)"));
    }
    let bodies: Vec<Result<PathBuf, String>> = members.iter().map(|v| runner.body(v)).collect();
    let cases = cases(members, &bodies, runner.request.rounding);
    let fields = in_parallel(&cases, runner.request.jobs, |case| {
        let field = case
            .run(runner, scenario_step, &[])
            .and_then(|dir| RunField::read(&dir).map_err(|e| e.to_string()));
        eprintln!(
            "{}: {}",
            case.label(),
            field.as_ref().map_or_else(Clone::clone, |_| "run".into())
        );
        field
    })?;
    let reference =
        cases.iter().zip(&fields).find(|(c, _)| c.variant.name == REFERENCE && c.j == 0);
    let reference = match reference {
        Some((_, Ok(field))) => field,
        Some((_, Err(why))) => return Err(format!("{REFERENCE}: {why}")),
        None => return Err(format!("no unperturbed {REFERENCE} run")),
    };
    let phase = Some(measure.phase.as_str());
    for &kind in &measure.kinds {
        let decomposed: Vec<Result<Decomposition, String>> = fields
            .iter()
            .map(|f| {
                let field = f.as_ref().map_err(Clone::clone)?;
                Decomposition::of(field, phase, kind).map_err(|e| e.to_string())
            })
            .collect();
        let base = Decomposition::of(reference, phase, kind)
            .map_err(|e| format!("{REFERENCE}, {kind}: {e}"))?;
        let modes = decomposed.iter().map(|d| d.as_ref().map_err(Clone::clone).map(modes_row));
        println!("\nModes of phase {}, {kind}:\n", measure.phase);
        print_table(&MODES_COLUMNS, &cases, &modes.collect::<Vec<_>>());
        let basis = decomposed.iter().map(|d| basis_row(d.as_ref().map_err(Clone::clone)?, &base));
        println!("\nBasis against {REFERENCE}'s, phase {}, {kind}:\n", measure.phase);
        print_table(&BASIS_COLUMNS, &cases, &basis.collect::<Vec<_>>());
    }
    Ok(())
}

/// The modes table's numbers of `d`.
fn modes_row(d: &Decomposition) -> Vec<Option<f64>> {
    let energy = d.pod.energy_fractions();
    let mut row = vec![Some(d.field.frames() as f64), Some(d.field.dofs() as f64)];
    row.extend((0..4).map(|i| energy.get(i).map(|e| 100.0 * e)));
    row.extend(d.modes_for_levels().map(|n| Some(n as f64)));
    let wave = d.wave.as_ref();
    row.extend([
        wave.map(|w| w.spatial.slope),
        wave.map(|w| w.spatial.r_squared),
        wave.map(|w| w.temporal.slope),
        wave.map(|w| w.temporal.r_squared),
        wave.map(|w| w.phase_speed_cm_s),
        wave.and_then(|w| w.knot).map(|k| k.slope),
        wave.and_then(|w| w.knot).map(|k| k.r_squared),
        wave.and_then(|w| w.speed_ratio),
    ]);
    row
}

/// The basis table's numbers of `d` against `base`.
fn basis_row(d: &Decomposition, base: &Decomposition) -> Result<Vec<Option<f64>>, String> {
    let angles = Comparison::of(d, base, ANGLE_MODES).map_err(|e| e.to_string())?;
    let most = CAPTURE_MODES.iter().copied().max().unwrap_or(1);
    let captured = Comparison::of(d, base, most).map_err(|e| e.to_string())?;
    let mut row: Vec<Option<f64>> =
        (0..ANGLE_MODES).map(|i| angles.principal_angles_deg.get(i).copied()).collect();
    for k in CAPTURE_MODES {
        row.push(captured.captured_by_other.get(k - 1).map(|e| 100.0 * e));
        row.push(captured.own_cumulative.get(k - 1).map(|e| 100.0 * e));
    }
    Ok(row)
}

/// Prints a Markdown table of `columns`: a row per case (its numbers, or why there are none),
/// and after each member's runs, when there are several, the spread of each column over them.
fn print_table(columns: &[Column], cases: &[Case<'_>], rows: &[Result<Vec<Option<f64>>, String>]) {
    let headers: Vec<&str> = columns.iter().map(|c| c.0).collect();
    println!("| run | {} |", headers.join(" | "));
    println!("|---|{}", "---|".repeat(columns.len()));
    for (i, (case, row)) in cases.iter().zip(rows).enumerate() {
        match row {
            Ok(values) => {
                let cells = columns.iter().zip(values).map(|(c, v)| cell(c, *v, *v));
                println!("| {} | {} |", case.label(), cells.collect::<Vec<_>>().join(" | "));
            }
            Err(why) => {
                println!("| {} | — ({why}) |{}", case.label(), " |".repeat(columns.len() - 1))
            }
        }
        let last_of_member = cases.get(i + 1).is_none_or(|next| next.j == 0);
        if last_of_member && case.j > 0 {
            let first = i - case.j;
            print_spread(columns, case.variant.name, &rows[first..=i]);
        }
    }
}

/// The row of the spread (min – max) of each column over `rows`, the runs of `name`.
fn print_spread(columns: &[Column], name: &str, rows: &[Result<Vec<Option<f64>>, String>]) {
    let measured: Vec<&Vec<Option<f64>>> = rows.iter().filter_map(|r| r.as_ref().ok()).collect();
    let cells = columns.iter().enumerate().map(|(c, column)| {
        let values = measured.iter().filter_map(|row| row[c]);
        let (low, high) = values.fold((None, None), |(lo, hi): (Option<f64>, Option<f64>), v| {
            (Some(lo.map_or(v, |l| l.min(v))), Some(hi.map_or(v, |h| h.max(v))))
        });
        cell(column, low, high)
    });
    let cells: Vec<String> = cells.collect();
    println!(
        "| **{name}: spread over {} of {} runs** | {} |",
        measured.len(),
        rows.len(),
        cells.join(" | ")
    );
}

/// A cell: `low` with the column's decimals, or `low – high` where they print differently;
/// `—` without a value.
fn cell(column: &Column, low: Option<f64>, high: Option<f64>) -> String {
    let show = |v: f64| format!("{v:.*}", column.1);
    match (low, high) {
        (Some(low), Some(high)) if show(low) != show(high) => {
            format!("{} – {}", show(low), show(high))
        }
        (Some(low), _) => show(low),
        _ => "—".into(),
    }
}
