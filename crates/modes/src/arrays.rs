//! A decomposition as named NumPy arrays: what `modes.npz` holds per selection and what the
//! Python package's `Run.modes` returns.

use std::path::{Path, PathBuf};

use hagfish_run::{NpyData, NpzEntry};

use crate::error::ModesError;
use crate::output::{Decomposition, MODES_DIR};
use crate::pod::ENERGY_LEVELS;

/// The archive `hagfish modes` writes into `RUN_DIR/modes/`.
pub const NPZ_FILE: &str = "modes.npz";

impl Decomposition {
    /// The decomposition as named arrays, the first `modes` modes' shapes and time courses
    /// (every mode's singular value and energy):
    ///
    /// | name | shape | meaning |
    /// |---|---|---|
    /// | `singular_values` | (r,) | σᵢ (dyn·cm) |
    /// | `energy_fractions`, `cumulative_fractions` | (r,) | σᵢ²/Σσ², their running sum |
    /// | `energy_levels`, `modes_for` | (3,) | 0.90, 0.95, 0.99 and the modes each needs (int64) |
    /// | `shapes` | (k, DOFs) | vᵢ(s), unit norm over the DOFs |
    /// | `s_cm`, `s_L` | (DOFs,) | each DOF's arc length from the head body's centre (cm, /L) |
    /// | `axis` | (DOFs,) | each DOF's axis: `X` twist, `Y`, `Z` bends (unicode) |
    /// | `time_s` | (frames,) | each frame's time |
    /// | `time_courses` | (k, frames) | aᵢ(t) = σᵢuᵢ(t) (dyn·cm) |
    /// | `knot_cm` | (frames,) | the knotted core's head-ward end (cm; NaN without a knot) |
    /// | `length_cm` | () | the body length L |
    /// | `wave` | (7,) | modes 1–2 as a wave: k (rad/cm), its R², ω (rad/s), its R², c = ω/k (cm/s), the knot's speed (cm/s), c / knot speed; NaN where there is none |
    pub fn arrays(&self, modes: usize) -> Vec<NpzEntry> {
        let (field, pod) = (&self.field, &self.pod);
        let kept = modes.min(pod.modes());
        let nan = f64::NAN;
        let wave = self.wave.as_ref().map_or([nan; 7], |w| {
            [
                w.spatial.slope,
                w.spatial.r_squared,
                w.temporal.slope,
                w.temporal.r_squared,
                w.phase_speed_cm_s,
                w.knot.map_or(nan, |k| k.slope),
                w.speed_ratio.unwrap_or(nan),
            ]
        });
        let modes_for = self.modes_for_levels().iter().map(|&n| n as i64).collect();
        let axis = self.dof_kinds.iter().map(|k| k.axis().to_string()).collect();
        vec![
            NpzEntry::vector("singular_values", pod.singular_values.clone()),
            NpzEntry::vector("energy_fractions", pod.energy_fractions()),
            NpzEntry::vector("cumulative_fractions", pod.cumulative_fractions()),
            NpzEntry::vector("energy_levels", ENERGY_LEVELS.to_vec()),
            NpzEntry { name: "modes_for".into(), shape: vec![3], data: NpyData::I64(modes_for) },
            NpzEntry::matrix("shapes", &pod.shapes[..kept], field.dofs()),
            NpzEntry::vector("s_cm", field.arcs_cm.clone()),
            NpzEntry::vector("s_L", field.arcs_l()),
            NpzEntry { name: "axis".into(), shape: vec![field.dofs()], data: NpyData::Text(axis) },
            NpzEntry::vector("time_s", field.times.clone()),
            NpzEntry::matrix("time_courses", &pod.time_courses[..kept], field.frames()),
            NpzEntry::vector("knot_cm", field.knot_cm.iter().map(|k| k.unwrap_or(nan)).collect()),
            NpzEntry::scalar("length_cm", field.length_cm),
            NpzEntry::vector("wave", wave.to_vec()),
        ]
    }
}

/// Writes `RUN_DIR/modes/modes.npz`: each decomposition's [`Decomposition::arrays`] named
/// `KIND/NAME` (`numpy.load(path)["bend-y/shapes"]`). Returns the file's path.
pub fn write_npz(
    directory: &Path,
    decompositions: &[Decomposition],
    modes: usize,
) -> Result<PathBuf, ModesError> {
    let path = directory.join(MODES_DIR).join(NPZ_FILE);
    let entries: Vec<NpzEntry> = decompositions
        .iter()
        .flat_map(|d| {
            d.arrays(modes).into_iter().map(move |mut e| {
                e.name = format!("{}/{}", d.kind, e.name);
                e
            })
        })
        .collect();
    hagfish_run::write_npz(&path, &entries)?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::Field;
    use crate::pod::Pod;
    use hagfish_control::{DofKind, KindSelection};

    #[test]
    fn the_arrays_hold_the_kept_modes_and_every_energy() -> Result<(), ModesError> {
        let (times, arcs) = (vec![0.0, 0.1, 0.2], vec![0.0, 1.0, 2.0, 3.0]);
        let values = vec![1.0, 0.0, 2.0, 0.0, 0.0, 1.0, 0.0, 3.0, 1.0, 1.0, 1.0, -1.0];
        let field =
            Field::new("test".into(), times, arcs, 10.0, vec![None, Some(1.0), None], values)?;
        let pod = Pod::of(&field)?;
        let d = Decomposition {
            kind: KindSelection::BendY,
            dof_kinds: vec![DofKind::BendY; 4],
            field,
            pod,
            wave: None,
        };
        let arrays = d.arrays(2);
        let get = |name: &str| arrays.iter().find(|e| e.name == name).expect(name);
        assert_eq!(get("shapes").shape, [2, 4]);
        assert_eq!(get("time_courses").shape, [2, 3]);
        assert_eq!(get("energy_fractions").shape, [3]);
        assert_eq!(get("s_L").data, NpyData::F64(vec![0.0, 0.1, 0.2, 0.3]));
        let NpyData::F64(knot) = &get("knot_cm").data else { panic!("knot_cm is float") };
        assert!(knot[0].is_nan() && knot[1] == 1.0);
        let NpyData::F64(wave) = &get("wave").data else { panic!("wave is float") };
        assert!(wave.iter().all(|w| w.is_nan()), "no wave fit, all NaN");
        for entry in &arrays {
            entry.npy_bytes()?;
        }
        Ok(())
    }
}
