//! Resolving a scenario's knot templates ([`hagfish_control::FollowPhase`]): the vertex file
//! each names (docs/knot-plans.md, "Templates") read at load and placed (mirrored if asked, its
//! first segment along +X), and checked to fit the body, so that a bad template is refused
//! before a run starts.

use std::path::Path;
use std::sync::Arc;

use hagfish_anatomy::DataFile;
use hagfish_control::{KnotTemplate, Phase};
use hagfish_tree::Model;

use crate::error::ScenarioError;
use crate::polyline_shape::read_vertices;
use crate::scenario::Scenario;

/// `phases` with each follow phase's template file made absolute (relative to `directory`, the
/// scenario file's) and its vertices read and placed. Errors give the scenario's position of
/// the template's `file` and what is wrong: unreadable, not a curve (with its line), a knot
/// name the analysis does not know, or a template longer than the body (`model`) at its scale.
pub(crate) fn resolve_knot_templates(
    file: &DataFile<Scenario>,
    directory: &Path,
    model: &Model,
    mut phases: Vec<Phase>,
) -> Result<Vec<Phase>, ScenarioError> {
    let length: f64 = model.bodies().iter().map(|b| b.length).sum();
    for phase in &mut phases {
        let Phase::Follow(follow) = phase else { continue };
        let written = follow.template.file.to_string_lossy().into_owned();
        let path = directory.join(&follow.template.file);
        let refuse = |reason: String| ScenarioError::KnotTemplateFile {
            at: file.locate_string("file", &written),
            reason: format!("{}: {reason}", path.display()),
        };
        let raw = read_vertices(&path, 1.0).map_err(refuse)?;
        let placed = KnotTemplate::placed(&raw, follow.template.mirror)
            .ok_or_else(|| refuse("the first two vertices coincide".into()))?;
        if hagfish_knots::KnotType::from_rolfsen_name(&follow.template.knot).is_none() {
            return Err(refuse(format!(
                "knot {:?} is not one the knot analysis names (0_1, 3_1, 4_1, 5_1, 5_2, 6_1, 6_2, 6_3)",
                follow.template.knot
            )));
        }
        follow.template.vertices = Some(Arc::new(placed));
        let on_body = follow.on_body(model.bodies());
        if on_body.length_cm() >= length {
            return Err(refuse(format!(
                "the template is {:.1} cm long on this body ({:.2} cm per unit), the body {length:.1} cm: use a smaller diameters_per_unit or a longer body",
                on_body.length_cm(),
                on_body.cm_per_unit
            )));
        }
        follow.template.file = std::fs::canonicalize(&path).unwrap_or(path);
    }
    Ok(phases)
}
