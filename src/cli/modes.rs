//! `hagfish modes RUN_DIR [--phase NAME] [--kind KIND] [--modes K] [--against OTHER]`: the
//! proper orthogonal decomposition of a run's thigmotaxis force field (`hagfish_modes`):
//! prints, per DOF selection, the energy of the first K modes, the modes needed for 90, 95 and
//! 99 % of the energy and the travelling-wave fit of modes 1 and 2; writes `RUN_DIR/modes/`.
//! With `--against OTHER`, instead, per one-kind selection: the principal angles between the
//! two runs' first K modes and the energy of RUN_DIR's field that OTHER's first 1…K modes
//! capture; writes `RUN_DIR/modes/against.json`.

use std::io::Write;
use std::path::PathBuf;

use hagfish_modes::{
    Comparison, Decomposition, ENERGY_LEVELS, KindSelection, ModesError, RunField, write_against,
};

use super::CliError;

/// Arguments of `hagfish modes`.
#[derive(Debug, clap::Args)]
pub struct ModesArgs {
    /// A run directory written by `hagfish run`.
    dir: PathBuf,
    /// The frames of this phase (`metrics.csv`'s `phase`, e.g. `slide`); default: every
    /// frame whose force field is not all zero.
    #[arg(long)]
    phase: Option<String>,
    /// The DOFs: all, bend (Y and Z), bend-y, bend-z or twist; default: each of them (a
    /// selection whose field is zero is then left out with a note); with `--against`, one kind
    /// (bend-y, bend-z or twist), by default each of the three.
    #[arg(long, value_parser = str::parse::<KindSelection>)]
    kind: Option<KindSelection>,
    /// The modes printed and written (shapes and time courses); with `--against`, the modes
    /// compared.
    #[arg(long, default_value_t = 8)]
    modes: usize,
    /// Another run directory: compare this run's modes with its modes on the same phase and
    /// kind (principal angles, the energy its modes capture of this run's field).
    #[arg(long, value_name = "OTHER_RUN_DIR")]
    against: Option<PathBuf>,
    /// Also write each selection's field rebuilt from its first K modes on every DOF
    /// (`modes/replay_KIND_kK.csv`, `replay_KIND_all.csv` for K ≥ the modes there are: the
    /// recorded field) for an open-loop replay (`parameters.replay`).
    #[arg(long, value_name = "K")]
    replay: Option<usize>,
}

/// The one-kind selections `--against` compares by default.
const ONE_KIND: [KindSelection; 3] =
    [KindSelection::BendY, KindSelection::BendZ, KindSelection::Twist];

/// Decomposes the run's field and writes `RUN_DIR/modes/`.
pub fn run(args: &ModesArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let field = RunField::read(&args.dir)?;
    let phase = args.phase.as_deref();
    if let Some(other) = &args.against {
        return against(args, &field, &RunField::read(other)?, out);
    }
    let kinds = args.kind.map_or(KindSelection::EVERY.to_vec(), |k| vec![k]);
    let mut decompositions = Vec::new();
    for kind in kinds {
        if let Some(d) = decompose(&field, phase, kind, args.kind.is_none(), out)? {
            decompositions.push(d);
        }
    }
    for d in &decompositions {
        print(d, args.modes, out)?;
    }
    let mut files = hagfish_modes::write_outputs(&args.dir, phase, &decompositions, args.modes)?;
    if let Some(k) = args.replay {
        for d in &decompositions {
            files.push(hagfish_modes::write_replay(d, &field, k)?);
        }
    }
    for file in files {
        writeln!(out, "wrote {}", file.display())?;
    }
    Ok(())
}

/// The decomposition of `kind`; `None`, with a note, for a zero field of a kind other than
/// `all` when the kind was not asked for by name (`defaulted`).
fn decompose(
    field: &RunField,
    phase: Option<&str>,
    kind: KindSelection,
    defaulted: bool,
    out: &mut dyn Write,
) -> Result<Option<Decomposition>, CliError> {
    match Decomposition::of(field, phase, kind) {
        Ok(d) => Ok(Some(d)),
        Err(ModesError::ZeroField { what }) if defaulted && kind != KindSelection::All => {
            writeln!(out, "{what}: the field is zero, left out")?;
            Ok(None)
        }
        Err(e) => Err(e.into()),
    }
}

/// `--against`: each one-kind selection of `run` against the same of `other`, printed and
/// written into `RUN_DIR/modes/against.json`.
fn against(
    args: &ModesArgs,
    run: &RunField,
    other: &RunField,
    out: &mut dyn Write,
) -> Result<(), CliError> {
    let phase = args.phase.as_deref();
    let kinds = args.kind.map_or(ONE_KIND.to_vec(), |k| vec![k]);
    let mut comparisons = Vec::new();
    for kind in kinds {
        let Some(mine) = decompose(run, phase, kind, args.kind.is_none(), out)? else {
            continue;
        };
        let theirs = Decomposition::of(other, phase, kind)
            .map_err(|e| ModesError::Incompatible(format!("{}: {e}", other.directory.display())))?;
        let c = Comparison::of(&mine, &theirs, args.modes)?;
        writeln!(
            out,
            "{} against {}: {} × {} against {} × {} (frames × DOFs)",
            mine.field.label,
            other.directory.display(),
            c.size[0],
            c.size[1],
            c.other_size[0],
            c.other_size[1]
        )?;
        writeln!(
            out,
            "angle_k: the k-th principal angle between the {n}-mode spans; own_cum, \
             captured_by_other: the energy of this field in its own, the other's first k modes",
            n = c.principal_angles_deg.len()
        )?;
        writeln!(
            out,
            "{:>3}  {:>15}  {:>12}  {:>20}",
            "k", "angle_k_deg", "own_cum_%", "captured_by_other_%"
        )?;
        for (i, angle) in c.principal_angles_deg.iter().enumerate() {
            let (own, captured) = (100.0 * c.own_cumulative[i], 100.0 * c.captured_by_other[i]);
            writeln!(out, "{:>3}  {angle:>15.6}  {own:>12.3}  {captured:>20.3}", i + 1)?;
        }
        writeln!(out)?;
        comparisons.push(c);
    }
    let file = write_against(&args.dir, &other.directory, phase, &comparisons)?;
    writeln!(out, "wrote {}", file.display())?;
    Ok(())
}

/// One selection's table, counts and wave fit.
fn print(d: &Decomposition, modes: usize, out: &mut dyn Write) -> Result<(), CliError> {
    let (first, last) = (d.field.times[0], d.field.times[d.field.frames() - 1]);
    writeln!(
        out,
        "{}: {} frames ({first:.2}–{last:.2} s) × {} DOFs",
        d.field.label,
        d.field.frames(),
        d.field.dofs()
    )?;
    writeln!(
        out,
        "{:>6}  {:>12}  {:>9}  {:>13}",
        "mode", "sigma_dyn_cm", "energy_%", "cumulative_%"
    )?;
    let (energy, cumulative) = (d.pod.energy_fractions(), d.pod.cumulative_fractions());
    for i in 0..modes.min(d.pod.modes()) {
        let sigma = d.pod.singular_values[i];
        let (e, c) = (100.0 * energy[i], 100.0 * cumulative[i]);
        writeln!(out, "{:>6}  {sigma:>12.4e}  {e:>9.3}  {c:>13.3}", i + 1)?;
    }
    let counts: Vec<String> = ENERGY_LEVELS
        .iter()
        .zip(d.modes_for_levels())
        .map(|(level, n)| format!("{:.0} %: {n}", 100.0 * level))
        .collect();
    writeln!(out, "modes for {}", counts.join(", "))?;
    match &d.wave {
        Some(w) => {
            let knot = w.knot.map_or("no knot position in these frames".into(), |k| {
                format!("knot_core_start_cm speed {:.4} cm/s (R² {:.3})", k.slope, k.r_squared)
            });
            let ratio = w.speed_ratio.map_or("-".into(), |r| format!("{r:.3}"));
            writeln!(
                out,
                "wave of modes 1–2: k {:.4} rad/cm (R² {:.3}), ω {:.4} rad/s (R² {:.3}), c = ω/k {:.4} cm/s; {knot}; c / knot speed {ratio}",
                w.spatial.slope,
                w.spatial.r_squared,
                w.temporal.slope,
                w.temporal.r_squared,
                w.phase_speed_cm_s
            )?;
        }
        None => writeln!(out, "wave of modes 1–2: the field has a single mode")?,
    }
    writeln!(out)?;
    Ok(())
}
