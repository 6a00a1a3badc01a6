//! The modes section of `report.html`: per thigmotaxis phase, the modes for 90, 95 and 99 %
//! of the field's energy and the travelling-wave fit of each DOF selection, and the first
//! four mode shapes of each one-kind selection.

use std::fmt::Write as _;
use std::path::Path;

use hagfish_report::{Section, draw_line_plot};

use crate::error::ModesError;
use crate::output::{Decomposition, MODES_DIR, shape_plot};
use crate::run_field::RunField;
use hagfish_control::KindSelection;

/// The `id` of the section's element.
pub const SECTION_ID: &str = "modes";

/// The section's heading.
pub const SECTION_TITLE: &str = "Modes of the force field";

/// The modes section of the run in `directory`: one table per phase whose thigmotaxic field
/// is not zero (in the run's order), with the first four mode shapes of its bend-y, bend-z
/// and twist selections; `None` when no phase has force.
pub fn report_section(directory: &Path) -> Result<Option<Section>, ModesError> {
    let run = RunField::read(directory)?;
    let mut phases = run.phases.clone();
    phases.dedup();
    let mut html = String::from(
        "<p>The proper orthogonal decomposition of the thigmotaxic force field \
         (<code>thigmo_force.npy</code>) on each phase with force: the modes needed for 90, 95 \
         and 99 % of the field's energy Σσ², the first four modes' energies, and modes 1–2 \
         read as a wave cos(θ(s) − ψ(t)): k = dθ/ds, ω = dψ/dt, its phase speed c = ω/k \
         (&gt; 0 tail-ward) against the knot's speed (the slope of \
         <code>knot_core_start_cm</code>). <code>hagfish modes DIR --phase NAME</code> writes \
         the arrays and the plots into <code>modes/</code> (docs/physics.md, “Modes of the \
         force field”).</p>\n",
    );
    let mut figures = Vec::new();
    let mut any = false;
    for phase in &phases {
        let mut decompositions = Vec::new();
        for kind in KindSelection::EVERY {
            match Decomposition::of(&run, Some(phase), kind) {
                Ok(d) => decompositions.push(d),
                Err(ModesError::ZeroField { .. }) => {}
                Err(e) => return Err(e),
            }
        }
        if decompositions.is_empty() {
            continue;
        }
        any = true;
        html.push_str(&table(phase, &decompositions));
        let folder = directory.join(MODES_DIR);
        for d in decompositions.iter().filter(|d| is_one_kind(d.kind)) {
            let (stem, plot) = shape_plot(d);
            let stem = format!("{stem}_{phase}");
            figures.push(draw_line_plot(&stem, &plot, &folder.join(format!("{stem}.png")))?);
        }
    }
    Ok(any.then(|| Section {
        id: SECTION_ID.into(),
        title: SECTION_TITLE.into(),
        html,
        figures,
        folder: None,
    }))
}

/// The sections `report.html` gets from this crate: the modes section of the run in
/// `directory` if a phase has force, or, if the field cannot be read or decomposed, a
/// section saying why (a report is still written).
pub fn report_sections(directory: &Path) -> Vec<Section> {
    match report_section(directory) {
        Ok(section) => section.into_iter().collect(),
        Err(e) => vec![Section {
            id: SECTION_ID.into(),
            title: SECTION_TITLE.into(),
            html: format!("<p>Not computed: {}</p>\n", hagfish_report::escape(&e.to_string())),
            figures: Vec::new(),
            folder: None,
        }],
    }
}

/// Whether `kind` selects DOFs of one kind, whose arc lengths are distinct.
fn is_one_kind(kind: KindSelection) -> bool {
    !matches!(kind, KindSelection::All | KindSelection::Bend)
}

/// The table of one phase.
fn table(phase: &str, decompositions: &[Decomposition]) -> String {
    let esc = hagfish_report::escape;
    let mut out = format!(
        "<h3>Phase {}</h3>\n<table>\n<tr><th>DOFs</th><th>frames × DOFs</th><th>modes for 90 \
         %</th><th>95 %</th><th>99 %</th><th>energy of modes 1–4 (%)</th><th>k (rad/cm, \
         R²)</th><th>ω (rad/s, R²)</th><th>c = ω/k (cm/s)</th><th>knot speed (cm/s)</th>\
         <th>c / knot speed</th></tr>\n",
        esc(phase)
    );
    for d in decompositions {
        let [n90, n95, n99] = d.modes_for_levels();
        let energies: Vec<String> =
            d.pod.energy_fractions().iter().take(4).map(|e| format!("{:.1}", 100.0 * e)).collect();
        let cells = match &d.wave {
            Some(w) => [
                format!("{:.4} ({:.2})", w.spatial.slope, w.spatial.r_squared),
                format!("{:.3} ({:.2})", w.temporal.slope, w.temporal.r_squared),
                format!("{:.3}", w.phase_speed_cm_s),
                w.knot.map_or("–".into(), |k| format!("{:.3}", k.slope)),
                w.speed_ratio.map_or("–".into(), |r| format!("{r:.2}")),
            ],
            None => ["–".into(), "–".into(), "–".into(), "–".into(), "–".into()],
        };
        let _ = write!(
            out,
            "<tr><td>{}</td><td>{} × {}</td><td>{n90}</td><td>{n95}</td><td>{n99}</td><td>{}</td>",
            esc(d.kind.name()),
            d.field.frames(),
            d.field.dofs(),
            energies.join(", ")
        );
        for cell in cells {
            let _ = write!(out, "<td>{}</td>", esc(&cell));
        }
        out.push_str("</tr>\n");
    }
    out.push_str("</table>\n");
    out
}
