//! Resolving a scenario's planned knots ([`hagfish_control::TieKnot::Planned`]): the plan file
//! each names (docs/knot-plans.md) read and checked at load, so that a bad plan is refused
//! before a run starts, with the plan file's own line and column where it has one.

use std::path::Path;
use std::sync::Arc;

use hagfish_anatomy::DataFile;
use hagfish_control::{KnotPlan, Phase, TieKnot};

use crate::error::ScenarioError;
use crate::scenario::Scenario;

/// `phases` with each planned knot's file made absolute (relative to `directory`, the scenario
/// file's) and its plan read. Errors give the scenario's position of the knot's `file` and
/// what is wrong with the plan (unreadable, malformed at its `file:line:column`, or refused
/// by [`KnotPlan::check`]).
pub(crate) fn resolve_knot_plans(
    file: &DataFile<Scenario>,
    directory: &Path,
    mut phases: Vec<Phase>,
) -> Result<Vec<Phase>, ScenarioError> {
    for phase in &mut phases {
        let Phase::Tie(tie) = phase else { continue };
        let TieKnot::Planned(planned) = &mut tie.knot else { continue };
        let path = directory.join(&planned.file);
        let plan = DataFile::<KnotPlan>::read(&path).map_err(|e| e.to_string()).and_then(|read| {
            read.value.check().map_err(|reason| format!("{}: {reason}", path.display()))?;
            Ok(read.value)
        });
        let plan = plan.map_err(|reason| ScenarioError::KnotPlanFile {
            at: file.locate_string("file", &planned.file.to_string_lossy()),
            reason,
        })?;
        planned.file = std::fs::canonicalize(&path).unwrap_or(path);
        planned.plan = Some(Arc::new(plan));
    }
    Ok(phases)
}
