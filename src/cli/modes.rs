//! `hagfish modes RUN_DIR [--phase NAME] [--kind KIND] [--modes K]`: the proper orthogonal
//! decomposition of a run's thigmotaxis force field (`hagfish_modes`): prints, per DOF
//! selection, the energy of the first K modes, the modes needed for 90, 95 and 99 % of the
//! energy and the travelling-wave fit of modes 1 and 2; writes `RUN_DIR/modes/`.

use std::io::Write;
use std::path::PathBuf;

use hagfish_modes::{Decomposition, ENERGY_LEVELS, KindSelection, ModesError, RunField};

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
    /// selection whose field is zero is then left out with a note).
    #[arg(long, value_parser = str::parse::<KindSelection>)]
    kind: Option<KindSelection>,
    /// The modes printed and written (shapes and time courses).
    #[arg(long, default_value_t = 8)]
    modes: usize,
}

/// Decomposes the run's field and writes `RUN_DIR/modes/`.
pub fn run(args: &ModesArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let field = RunField::read(&args.dir)?;
    let phase = args.phase.as_deref();
    let kinds = args.kind.map_or(KindSelection::EVERY.to_vec(), |k| vec![k]);
    let mut decompositions = Vec::new();
    for kind in kinds {
        match Decomposition::of(&field, phase, kind) {
            Ok(d) => decompositions.push(d),
            Err(ModesError::ZeroField { what })
                if args.kind.is_none() && kind != KindSelection::All =>
            {
                writeln!(out, "{what}: the field is zero, left out")?;
            }
            Err(e) => return Err(e.into()),
        }
    }
    for d in &decompositions {
        print(d, args.modes, out)?;
    }
    let files = hagfish_modes::write_outputs(&args.dir, phase, &decompositions, args.modes)?;
    for file in files {
        writeln!(out, "wrote {}", file.display())?;
    }
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
