//! The replay file of a decomposition: its field rebuilt from its first K modes, on every DOF
//! of the body, for an open-loop replay (`hagfish_control::Replay`, `hagfish modes RUN_DIR
//! --phase P --replay K`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::ModesError;
use crate::output::{Decomposition, MODES_DIR};
use crate::run_field::RunField;

/// The field of `d` from its first `modes` modes, Σᵢ≤K aᵢ(t) vᵢ(s) (the recorded field itself,
/// exactly, when K is every mode), on all of `run`'s DOFs (zero on those `d` leaves out):
/// frames × DOFs, row-major (dyn·cm).
pub fn replay_values(d: &Decomposition, run: &RunField, modes: usize) -> Vec<f64> {
    let columns: Vec<usize> =
        (0..run.kinds.len()).filter(|&c| d.kind.includes(run.kinds[c])).collect();
    let (frames, width) = (d.field.frames(), run.kinds.len());
    let mut values = vec![0.0; frames * width];
    for f in 0..frames {
        for (j, &c) in columns.iter().enumerate() {
            values[f * width + c] = if modes >= d.pod.modes() {
                d.field.values[f * columns.len() + j]
            } else {
                (0..modes).map(|i| d.pod.time_courses[i][f] * d.pod.shapes[i][j]).sum()
            };
        }
    }
    values
}

/// Writes `RUN_DIR/modes/replay_KIND_kK.csv` (`replay_KIND_all.csv` when K is every mode):
/// `time_s` since the selection's first frame, then one column per DOF of the body
/// (`dof_0` … in tree order) holding [`replay_values`]. Returns the file's path.
pub fn write_replay(
    d: &Decomposition,
    run: &RunField,
    modes: usize,
) -> Result<PathBuf, ModesError> {
    let all = modes >= d.pod.modes();
    let name = if all {
        format!("replay_{}_all.csv", d.kind)
    } else {
        format!("replay_{}_k{modes}.csv", d.kind)
    };
    let path = run.directory.join(MODES_DIR).join(name);
    let values = replay_values(d, run, modes);
    let width = run.kinds.len();
    let mut text = String::from("time_s");
    for c in 0..width {
        let _ = write!(text, ",dof_{c}");
    }
    text.push('\n');
    let start = d.field.times[0];
    for (f, t) in d.field.times.iter().enumerate() {
        let _ = write!(text, "{}", t - start);
        for v in &values[f * width..(f + 1) * width] {
            let _ = write!(text, ",{v:e}");
        }
        text.push('\n');
    }
    write_text(&path, &text)?;
    Ok(path)
}

/// Writes `text` as `path`, creating its folder.
fn write_text(path: &Path, text: &str) -> Result<(), ModesError> {
    if let Some(folder) = path.parent() {
        std::fs::create_dir_all(folder)
            .map_err(|source| ModesError::Write { path: folder.into(), source })?;
    }
    hagfish_run::replace_file(path, text.as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pod::Pod;
    use hagfish_control::{DofKind, KindSelection};

    #[test]
    fn every_mode_gives_the_field_back_and_fewer_its_projection_on_the_selected_dofs() {
        // Three DOFs (twist, bend-y, bend-z); the bends selected: a rank-2 field.
        let run = RunField {
            directory: "unused".into(),
            times: vec![0.0, 0.1, 0.2],
            phases: vec!["slide".into(); 3],
            knot_cm: vec![None; 3],
            kinds: vec![DofKind::Twist, DofKind::BendY, DofKind::BendZ],
            arcs_cm: vec![1.0, 1.0, 1.0],
            length_cm: 10.0,
            values: vec![9.0, 1.0, 2.0, 9.0, -2.0, 0.5, 9.0, 0.5, -1.0],
        };
        let field = run.select(Some("slide"), KindSelection::Bend).expect("a field");
        let pod = Pod::of(&field).expect("a POD");
        let d = Decomposition {
            kind: KindSelection::Bend,
            dof_kinds: vec![DofKind::BendY, DofKind::BendZ],
            field,
            pod,
            wave: None,
        };
        let all = replay_values(&d, &run, 2);
        assert_eq!(all, [0.0, 1.0, 2.0, 0.0, -2.0, 0.5, 0.0, 0.5, -1.0]);
        let one = replay_values(&d, &run, 1);
        let v1 = &d.pod.shapes[0];
        for f in 0..3 {
            assert_eq!(one[3 * f], 0.0, "the twist is not selected");
            // F₁ = a₁v₁ᵀ: the residual of each frame is orthogonal to v₁, F₁ is along it.
            let residual: f64 =
                (0..2).map(|j| (all[3 * f + 1 + j] - one[3 * f + 1 + j]) * v1[j]).sum();
            assert!(residual.abs() < 1e-12, "frame {f}: {residual}");
            let cross = one[3 * f + 1] * v1[1] - one[3 * f + 2] * v1[0];
            assert!(cross.abs() < 1e-12, "frame {f}: F₁ along v₁");
        }
        assert_ne!(one, all, "one mode of a rank-2 field is not the field");
    }
}
