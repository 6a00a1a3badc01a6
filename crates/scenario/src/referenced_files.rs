//! The files a scenario reads besides itself and its body — an initial shape's vertices
//! ([`crate::PolylineShape`]), knot plans ([`hagfish_control::TieKnot::Planned`]), modal bases
//! ([`hagfish_control::ModalSpace`]) and replays ([`hagfish_control::Replay`]) — and a hash of
//! their bytes. Their contents are not
//! part of the resolved scenario text (only their paths are), so a resume compares this hash
//! with its checkpoint's: a run continued with an edited plan would not be the run it resumes.

use std::path::PathBuf;

use hagfish_anatomy::read_data_file;
use hagfish_control::{ForceSpace, Phase, TieKnot};
use hagfish_sim::fnv1a64;

use crate::error::ScenarioError;
use crate::initial_shape::InitialShape;
use crate::scenario::Scenario;

/// The files `scenario` reads, as the loaded scenario names them (absolute): its initial
/// shape's, then its phases' in phase order (a phase's knot plan or template, then its modal basis, then
/// its replay).
pub(crate) fn referenced_files(scenario: &Scenario) -> Vec<PathBuf> {
    let mut files = Vec::new();
    if let Some(InitialShape::Polyline(shape)) = &scenario.initial_shape {
        files.push(shape.file.clone());
    }
    for phase in &scenario.phases {
        match phase {
            Phase::Tie(tie) => {
                if let TieKnot::Planned(planned) = &tie.knot {
                    files.push(planned.file.clone());
                }
            }
            Phase::Follow(follow) => files.push(follow.template.file.clone()),
            Phase::Thigmotaxis(thigmo) => {
                if let ForceSpace::Modes(space) = &thigmo.parameters.force_space {
                    files.push(space.file.clone());
                }
                if let Some(replay) = &thigmo.parameters.replay {
                    files.push(replay.file.clone());
                }
            }
            _ => {}
        }
    }
    files
}

/// FNV-1a (16 hex digits) of the files' bytes, each preceded by its length as 8 little-endian
/// bytes (so that no two lists of contents run together into one); empty for no files.
///
/// # Errors
/// [`ScenarioError::DataFile`] if a file cannot be read.
pub(crate) fn referenced_files_hash(files: &[PathBuf]) -> Result<String, ScenarioError> {
    if files.is_empty() {
        return Ok(String::new());
    }
    let mut bytes = Vec::new();
    for file in files {
        let content = read_data_file(file)?;
        bytes.extend_from_slice(&(content.len() as u64).to_le_bytes());
        bytes.extend_from_slice(&content);
    }
    Ok(format!("{:016x}", fnv1a64(&bytes)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_files_hash_to_nothing_and_the_split_between_files_counts() {
        assert_eq!(referenced_files_hash(&[]).ok(), Some(String::new()));
        let dir = std::env::temp_dir().join(format!("hagfish_referenced_{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("a temporary directory");
        let write = |name: &str, text: &str| {
            let path = dir.join(name);
            std::fs::write(&path, text).expect("a file");
            path
        };
        let (ab, c) = (write("ab", "ab"), write("c", "c"));
        let (a, bc) = (write("a", "a"), write("bc", "bc"));
        let hash = |files: &[PathBuf]| referenced_files_hash(files).expect("readable");
        assert_ne!(hash(&[ab.clone(), c.clone()]), hash(&[a, bc]));
        assert_eq!(hash(&[ab.clone(), c.clone()]), hash(&[ab, c]));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
