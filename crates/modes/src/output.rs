//! The decomposition of one selection and the files `hagfish modes` writes into
//! `RUN_DIR/modes/`: `modes.csv`, `time_courses.csv`, `modes.json`, `modes.npz` and the plots.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use hagfish_report::{Line, Scatter, TimeSeries, write_line_plots, write_scatters};

use crate::error::ModesError;
use crate::field::Field;
use crate::pod::{ENERGY_LEVELS, Pod};
use crate::run_field::RunField;
use crate::wave::WaveFit;
use hagfish_control::{DofKind, KindSelection};

/// The folder of the run directory the outputs go to.
pub const MODES_DIR: &str = "modes";

/// The mode shapes drawn per selection.
const PLOTTED_MODES: usize = 4;

/// One selection's field, its POD and the travelling-wave fit of its first two modes
/// (`None` for a field with a single mode).
#[derive(Clone, Debug)]
pub struct Decomposition {
    /// The DOFs selected.
    pub kind: KindSelection,
    /// The kind of each selected DOF, in the field's column order (`modes.csv`'s `axis`).
    pub dof_kinds: Vec<DofKind>,
    /// The field.
    pub field: Field,
    /// Its POD.
    pub pod: Pod,
    /// The wave fit of modes 1 and 2.
    pub wave: Option<WaveFit>,
}

impl Decomposition {
    /// The decomposition of `run`'s field on the frames of `phase` and the DOFs of `kind`
    /// ([`RunField::select`]).
    pub fn of(
        run: &RunField,
        phase: Option<&str>,
        kind: KindSelection,
    ) -> Result<Self, ModesError> {
        let field = run.select(phase, kind)?;
        let dof_kinds = run.kinds.iter().copied().filter(|&k| kind.includes(k)).collect();
        let pod = Pod::of(&field)?;
        let wave = if pod.modes() >= 2 { Some(WaveFit::of(&pod, &field)?) } else { None };
        Ok(Self { kind, dof_kinds, field, pod, wave })
    }

    /// The number of modes for each of [`ENERGY_LEVELS`].
    pub fn modes_for_levels(&self) -> [usize; 3] {
        ENERGY_LEVELS.map(|level| self.pod.modes_for(level))
    }

    /// The summary of `modes.json`.
    fn summary(&self) -> serde_json::Value {
        serde_json::json!({
            "kind": self.kind.name(),
            "selection": self.field.label,
            "frames": self.field.frames(),
            "dofs": self.field.dofs(),
            "time_s": [self.field.times.first(), self.field.times.last()],
            "singular_values_dyn_cm": self.pod.singular_values,
            "energy_fractions": self.pod.energy_fractions(),
            "cumulative_fractions": self.pod.cumulative_fractions(),
            "modes_for": ENERGY_LEVELS.iter().zip(self.modes_for_levels())
                .map(|(l, n)| (format!("{l:.2}"), n.into()))
                .collect::<serde_json::Map<String, serde_json::Value>>(),
            "wave": self.wave,
        })
    }
}

/// Writes `decompositions` of the run at `directory` into `directory/modes/`: the shapes and
/// time courses of the first `modes` modes of each (long format CSV), `modes.json` (every
/// singular value, energies, the 90/95/99 % counts and the wave fits), `modes.npz` (the same
/// as NumPy arrays, [`Decomposition::arrays`]) and the plots (the
/// energy spectrum of each selection, and the first four shapes of each one-kind selection,
/// whose DOFs have distinct arc lengths). Returns the files written.
pub fn write_outputs(
    directory: &Path,
    phase: Option<&str>,
    decompositions: &[Decomposition],
    modes: usize,
) -> Result<Vec<PathBuf>, ModesError> {
    let out = directory.join(MODES_DIR);
    std::fs::create_dir_all(&out)
        .map_err(|source| ModesError::Write { path: out.clone(), source })?;
    let mut shapes = String::from("kind,mode,axis,s_cm,s_L,shape\n");
    let mut courses = String::from("kind,mode,time_s,amplitude_dyn_cm\n");
    for d in decompositions {
        let kept = modes.min(d.pod.modes());
        for (i, shape) in d.pod.shapes.iter().take(kept).enumerate() {
            for ((s, v), axis) in d.field.arcs_cm.iter().zip(shape).zip(&d.dof_kinds) {
                let (kind, mode, axis, s_l) = (d.kind, i + 1, axis.axis(), s / d.field.length_cm);
                let _ = writeln!(shapes, "{kind},{mode},{axis},{s},{s_l},{v:e}");
            }
        }
        for (i, course) in d.pod.time_courses.iter().take(kept).enumerate() {
            for (t, a) in d.field.times.iter().zip(course) {
                let _ = writeln!(courses, "{},{},{t},{a:e}", d.kind, i + 1);
            }
        }
    }
    let json = serde_json::json!({
        "run": directory.display().to_string(),
        "phase": phase,
        "mean_removed": false,
        "amplitude_threshold": crate::wave::AMPLITUDE_THRESHOLD,
        "knot_column": "knot_core_start_cm",
        "selections": decompositions.iter().map(Decomposition::summary).collect::<Vec<_>>(),
    });
    let text = serde_json::to_string_pretty(&json).unwrap_or_default();
    let mut files = Vec::new();
    for (name, bytes) in
        [("modes.csv", shapes), ("time_courses.csv", courses), ("modes.json", text)]
    {
        let path = out.join(name);
        hagfish_run::replace_file(&path, bytes.as_bytes())?;
        files.push(path);
    }
    files.push(crate::arrays::write_npz(directory, decompositions, modes)?);
    files.extend(write_scatters(&decompositions.iter().map(spectrum).collect::<Vec<_>>(), &out)?);
    let one_kind =
        decompositions.iter().filter(|d| d.field.arcs_cm.windows(2).all(|w| w[0] < w[1]));
    files.extend(write_line_plots(&one_kind.map(shape_plot).collect::<Vec<_>>(), &out)?);
    Ok(files)
}

/// The energy spectrum: each mode's energy (% of the field's) against its index.
fn spectrum(d: &Decomposition) -> Scatter {
    Scatter {
        stem: format!("energy_{}", d.kind),
        title: format!("Energy of each mode, {}", d.field.label),
        x_label: "mode".into(),
        y_label: "energy (% of ‖F‖²)".into(),
        points: d
            .pod
            .energy_fractions()
            .iter()
            .enumerate()
            .map(|(i, e)| ((i + 1) as f64, 100.0 * e))
            .collect(),
        intervals: Vec::new(),
    }
}

/// The first four mode shapes against s/L.
pub(crate) fn shape_plot(d: &Decomposition) -> (String, TimeSeries) {
    const COLOURS: [[u8; 3]; PLOTTED_MODES] =
        [[31, 119, 180], [214, 39, 40], [44, 160, 44], [148, 103, 189]];
    let energy = d.pod.energy_fractions();
    let lines = d.pod.shapes.iter().zip(COLOURS).enumerate().map(|(i, (shape, colour))| Line {
        label: format!("mode {} ({:.1} %)", i + 1, 100.0 * energy[i]),
        colour,
        values: shape.iter().map(|v| Some(*v)).collect(),
    });
    let plot = TimeSeries {
        title: format!("Mode shapes, {}", d.field.label),
        x_label: "arc length from the head, s/L".into(),
        y_label: "shape vᵢ(s) (unit norm)".into(),
        times: d.field.arcs_l(),
        lines: lines.collect(),
    };
    (format!("shapes_{}", d.kind), plot)
}
