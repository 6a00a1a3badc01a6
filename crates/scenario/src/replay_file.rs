//! Resolving a scenario's open-loop replays ([`hagfish_control::Replay`]): the CSV a replay
//! names (`hagfish modes RUN_DIR --phase P --replay K`: a `time_s` column, then one column
//! per DOF in tree order, dyn·cm) read at load, checked against the body's DOF count.

use std::path::Path;
use std::sync::Arc;

use hagfish_anatomy::DataFile;
use hagfish_control::{Phase, ReplayField};

use crate::error::ScenarioError;
use crate::scenario::Scenario;

/// `phases` with each replay's file made absolute (relative to `directory`, the scenario
/// file's) and its field read, for a body of `dofs` DOFs. Errors name the replay's `file`
/// (unreadable, malformed, another DOF count) at its `file:line:column`.
pub(crate) fn resolve_replays(
    file: &DataFile<Scenario>,
    directory: &Path,
    mut phases: Vec<Phase>,
    dofs: usize,
) -> Result<Vec<Phase>, ScenarioError> {
    for phase in &mut phases {
        let Phase::Thigmotaxis(thigmo) = phase else { continue };
        let Some(replay) = &mut thigmo.parameters.replay else { continue };
        let path = directory.join(&replay.file);
        let field = read(&path, dofs).map_err(|reason| ScenarioError::ModeFile {
            at: file.locate_string("file", &replay.file.to_string_lossy()),
            reason: format!("{}: {reason}", path.display()),
        })?;
        replay.file = std::fs::canonicalize(&path).unwrap_or(path);
        replay.field = Some(Arc::new(field));
    }
    Ok(phases)
}

/// The field of the replay CSV at `path` for a body of `dofs` DOFs.
fn read(path: &Path, dofs: usize) -> Result<ReplayField, String> {
    let mut reader = csv::Reader::from_path(path).map_err(|e| e.to_string())?;
    let header = reader.headers().map_err(|e| e.to_string())?;
    if header.get(0) != Some("time_s") || header.len() != dofs + 1 {
        return Err(format!(
            "expected the columns time_s and one per DOF ({} in all), found {}",
            dofs + 1,
            header.len()
        ));
    }
    let (mut times, mut values) = (Vec::new(), Vec::new());
    for (line, record) in reader.records().enumerate() {
        let record = record.map_err(|e| e.to_string())?;
        let mut numbers = record.iter().map(str::parse::<f64>);
        let bad = |what: &str| format!("row {}: {what}", line + 1);
        times.push(numbers.next().ok_or_else(|| bad("empty"))?.map_err(|e| bad(&e.to_string()))?);
        for number in numbers {
            values.push(number.map_err(|e| bad(&e.to_string()))?);
        }
    }
    ReplayField::new(times, dofs, values)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_replay_file_is_read_and_checked_against_the_dofs() -> Result<(), String> {
        let dir = std::env::temp_dir().join(format!("hagfish-replay-{}", std::process::id()));
        std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
        let path = dir.join("replay.csv");
        std::fs::write(&path, "time_s,d0,d1\n0,1,2\n0.1,3,4.5\n").map_err(|e| e.to_string())?;
        let field = read(&path, 2)?;
        let mut out = Vec::new();
        field.sample(0.1, &mut out);
        assert_eq!(out, [3.0, 4.5]);
        let wrong = read(&path, 3).expect_err("3 DOFs asked, 2 columns");
        assert!(wrong.contains("4 in all"), "{wrong}");
        std::fs::write(&path, "time_s,d0\n0,x\n").map_err(|e| e.to_string())?;
        assert!(read(&path, 1).expect_err("not a number").starts_with("row 1"));
        Ok(())
    }
}
