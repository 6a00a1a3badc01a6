//! Resolving a scenario's modal force spaces ([`ForceSpace::Modes`]) on its body: the first k
//! mode shapes of a `modes.csv` (`hagfish modes`: `kind,mode,axis,s_cm,s_L,shape`) read as
//! functions of s/L, one per DOF axis, resampled at this body's DOFs and orthonormalised.
//!
//! DOF d of the body, about axis a at arc-length fraction s_d/L (`rest_dof_arc_lengths`),
//! takes in mode j the value of the file's samples of mode j and axis a at s_d/L, linearly
//! interpolated (clamped beyond the first and last sample), when the kind selects axis a;
//! the DOFs of the other axes (the twists for `bend`, X and Z for `bend-y`, …) are zero.
//! The k vectors are then orthonormalised ([`ModalBasis::orthonormal`]), which refuses a set
//! that is rank-deficient on this body.

use std::path::Path;
use std::sync::Arc;

use hagfish_anatomy::{DataFile, Field, interpolate_clamped};
use hagfish_control::{DofKind, ForceSpace, ModalBasis, ModalSpace, Phase};
use hagfish_tree::Model;

use crate::error::ScenarioError;
use crate::scenario::Scenario;

/// One row of `modes.csv`, the columns a basis needs.
#[derive(serde::Deserialize)]
struct ShapeRow {
    kind: String,
    mode: usize,
    axis: char,
    #[serde(rename = "s_L")]
    s_l: f64,
    shape: f64,
}

/// The scenario's phases with each modal space's file made absolute (relative paths are
/// relative to `directory`, the scenario file's) and its basis resampled on `model` of length
/// `length_cm`. Errors name the space's `file` (unreadable, malformed, no modes of the kind)
/// or `modes` (more than the file has, rank-deficient) at its `file:line:column`.
pub(crate) fn resolve_modal_spaces(
    file: &DataFile<Scenario>,
    directory: &Path,
    model: &Model,
    length_cm: f64,
) -> Result<Vec<Phase>, ScenarioError> {
    let mut occurrence = 0;
    let mut phases = file.value.phases.clone();
    for phase in &mut phases {
        let Phase::Thigmotaxis(thigmo) = phase else { continue };
        let ForceSpace::Modes(space) = &mut thigmo.parameters.force_space else { continue };
        // `file` is a key of knot plans and replays too: found by its value; `modes` is
        // the modal spaces' own, found by its count.
        let at = |key| match key {
            "file" => file.locate_string("file", &space.file.to_string_lossy()),
            key => file.locate(&Field::nth(key, occurrence)),
        };
        let error = |key, reason: String| ScenarioError::ModeFile { at: at(key), reason };
        let path = directory.join(&space.file);
        let (vectors, available) = resample(&path, space, model, length_cm)
            .map_err(|reason| error("file", format!("{}: {reason}", path.display())))?;
        if space.modes > available {
            let (k, kind) = (space.modes, space.kind);
            let reason =
                format!("k = {k}, but {} has {available} modes of kind {kind}", path.display());
            return Err(error("modes", reason));
        }
        let basis = ModalBasis::orthonormal(model.dof_count(), &vectors)
            .map_err(|e| error("modes", format!("{}: {e}", path.display())))?;
        space.file = std::fs::canonicalize(&path).unwrap_or(path);
        space.basis = Some(Arc::new(basis));
        occurrence += 1;
    }
    Ok(phases)
}

/// The first `space.modes` shapes of `space.kind` in the file at `path`, each sampled at the
/// DOFs of `model` (module docs), and the number of modes of that kind the file holds.
fn resample(
    path: &Path,
    space: &ModalSpace,
    model: &Model,
    length_cm: f64,
) -> Result<(Vec<Vec<f64>>, usize), String> {
    let mut reader = csv::Reader::from_path(path).map_err(|e| e.to_string())?;
    // samples[j][axis]: (s/L, value) of mode j + 1 along one axis, in file order.
    let mut samples: Vec<[(Vec<f64>, Vec<f64>); 3]> = Vec::new();
    let mut available = 0;
    for row in reader.deserialize::<ShapeRow>() {
        let row = row.map_err(|e| e.to_string())?;
        if row.kind != space.kind.name() {
            continue;
        }
        let axis = DofKind::from_axis(row.axis)
            .ok_or_else(|| format!("axis {:?}: expected X, Y or Z", row.axis))?;
        if row.mode == 0 || !row.s_l.is_finite() || !row.shape.is_finite() {
            return Err(format!("mode {}: modes count from 1, values are finite", row.mode));
        }
        available = available.max(row.mode);
        if row.mode <= space.modes {
            samples.resize_with(samples.len().max(row.mode), Default::default);
            let (at, values) = &mut samples[row.mode - 1][axis as usize];
            if at.last().is_some_and(|&last| row.s_l <= last) {
                return Err(format!("mode {}, axis {}: s_L not increasing", row.mode, row.axis));
            }
            at.push(row.s_l);
            values.push(row.shape);
        }
    }
    if available == 0 {
        return Err(format!("no modes of kind {}", space.kind));
    }
    let arcs = hagfish_sim::rest_dof_arc_lengths(model);
    let labels = hagfish_sim::dof_labels(model);
    let mut vectors = Vec::with_capacity(samples.len());
    for (j, mode) in samples.iter().enumerate() {
        let mut vector = Vec::with_capacity(arcs.len());
        for (arc, label) in arcs.iter().zip(&labels) {
            let value = match DofKind::from_axis(label.axis) {
                Some(kind) if space.kind.includes(kind) => {
                    let (at, values) = &mode[kind as usize];
                    if at.is_empty() {
                        return Err(format!(
                            "mode {} has no samples of axis {}",
                            j + 1,
                            label.axis
                        ));
                    }
                    interpolate_clamped(at, values, arc / length_cm)
                }
                _ => 0.0,
            };
            vector.push(value);
        }
        vectors.push(vector);
    }
    Ok((vectors, available))
}
