//! Thigmotaxis confined to a modal force space (`ForceSpace::Modes`, `P = B Bᵀ`): with the
//! unit vectors as modes (B = I) the whole thesis run is the `Full` run bit for bit, and with a
//! few smooth modes the step's thigmotaxic force lies in span(B) to rounding.

use crate::freshly_tied::{freshly_tied_knot, thigmo_step};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use std::sync::Arc;

use hagfish_control::{ForceSpace, KindSelection, ModalBasis, ModalSpace};
use hagfish_run::{Frame, FrameSink, RunError, RunOptions};
use hagfish_scenario::LoadedScenario;
use hagfish_sim::{dof_labels, rest_dof_arc_lengths, state_hash};
use hagfish_tree::Model;

const THESIS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/scenarios/thesis.ron");

/// Records nothing.
struct Nothing;

impl FrameSink for Nothing {
    fn record(&mut self, _: &Frame<'_>) -> Result<(), RunError> {
        Ok(())
    }
}

/// A fresh directory for this test's files.
fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hagfish-modal-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    dir
}

/// Writes `modes` (each one value per DOF of `model`) as a `modes.csv` of kind `all` at
/// `path`, each value at its DOF's axis and s/L as `hagfish modes` writes them.
fn write_modes(path: &Path, model: &Model, length_cm: f64, modes: &[Vec<f64>]) {
    let (arcs, labels) = (rest_dof_arc_lengths(model), dof_labels(model));
    let mut text = String::from("kind,mode,axis,s_cm,s_L,shape\n");
    for (j, mode) in modes.iter().enumerate() {
        for ((s, label), v) in arcs.iter().zip(&labels).zip(mode) {
            let _ = writeln!(text, "all,{},{},{s},{},{v:e}", j + 1, label.axis, s / length_cm);
        }
    }
    std::fs::write(path, text).expect("modes.csv written");
}

/// thesis.ron with its tighten and slide phases confined to `space` (RON text), parsed as if
/// it sat where thesis.ron does.
fn thesis_confined_to(space: &str) -> LoadedScenario {
    let text = std::fs::read_to_string(THESIS).expect("thesis.ron");
    let text = text.replace(
        "max_force_dyn: 2000.0,",
        &format!("max_force_dyn: 2000.0, force_space: {space},"),
    );
    LoadedScenario::parse(text.as_bytes(), Path::new(THESIS)).expect("parses")
}

/// The final state hash of a whole run of `loaded`.
fn final_hash(loaded: &LoadedScenario) -> String {
    let outcome = hagfish_run::run(loaded, RunOptions::default(), &mut Nothing, &mut |_| {})
        .expect("run starts");
    let state = outcome.state.clone();
    outcome.finished().expect("run finishes");
    state_hash(&state)
}

/// B = I (k = n, the unit vectors read from a file): `c̃ = B(Bᵀc)` sums products with zeros
/// and ones only, so every row is the full row exactly and thesis.ron (tie, tighten and slide
/// confined) ends in the very state of the `Full` run.
#[test]
fn the_identity_basis_reproduces_the_full_run_bit_for_bit() {
    let full = LoadedScenario::load(THESIS).expect("thesis.ron loads");
    let model = full.body.to_model().expect("model");
    let n = model.dof_count();
    let unit = |i: usize| (0..n).map(|k| if k == i { 1.0 } else { 0.0 }).collect::<Vec<_>>();
    let file = scratch_dir("identity").join("modes.csv");
    write_modes(&file, &model, full.body.length_cm(), &(0..n).map(unit).collect::<Vec<_>>());
    let space = format!("Modes((file: {:?}, kind: \"all\", modes: {n}))", file.display());
    let modal = thesis_confined_to(&space);
    assert!(modal.resolved_text().contains("Modes("), "the spec stays in the scenario");
    assert!(!modal.resolved_text().contains("basis"), "the matrix is not serialised");
    assert_eq!(final_hash(&modal), final_hash(&full));
}

/// Four smooth modes (sines along the body, shifted on each axis): one thigmotaxis step from
/// a freshly tied knot (form.ron at 17 s, as `bending_only_rows_exert_no_twist_torque`)
/// exerts a thigmotaxic force `f = C_thᵀλ` that is not zero and lies in span(B),
/// `‖(I − BBᵀ)f‖ ≤ 1e-12 ‖f‖`, while the `Full` step's force does not.
#[test]
fn the_modal_thigmotaxic_force_lies_in_the_span_of_the_basis() {
    let (loaded, mut world, knotted) = freshly_tied_knot();
    let model = world.model().clone();
    let (arcs, labels) = (rest_dof_arc_lengths(&model), dof_labels(&model));
    let length = loaded.body.length_cm();
    let shape = |j: usize| -> Vec<f64> {
        let shift = |axis: char| f64::from(u32::from(axis) - u32::from('X'));
        let wave = |s: f64, a: f64| ((j as f64 + 1.0) * std::f64::consts::PI * s + a).sin();
        arcs.iter().zip(&labels).map(|(s, l)| wave(s / length, shift(l.axis))).collect()
    };
    let shapes: Vec<Vec<f64>> = (0..4).map(shape).collect();
    let basis = Arc::new(ModalBasis::orthonormal(model.dof_count(), &shapes).expect("a basis"));
    let modal = ForceSpace::Modes(ModalSpace {
        file: "synthetic".into(),
        kind: KindSelection::All,
        modes: 4,
        basis: Some(basis.clone()),
    });
    for (force_space, in_span) in [(ForceSpace::Full, false), (modal, true)] {
        let force = thigmo_step(&mut world, &knotted, force_space);
        let mut projected = force.clone();
        basis.project(&mut projected, &mut [0.0; 4]);
        let norm = force.iter().map(|f| f * f).sum::<f64>().sqrt();
        let off = force.iter().zip(&projected).map(|(f, p)| (f - p).powi(2)).sum::<f64>().sqrt();
        println!("in span {in_span}: ‖f‖ = {norm:e}, ‖(I − BBᵀ)f‖ = {off:e}");
        assert!(norm > 1.0, "a force of a dyn·cm or more: {norm:e}");
        assert_eq!(off <= 1e-12 * norm, in_span, "‖(I − BBᵀ)f‖ = {off:e}, ‖f‖ = {norm:e}");
    }
}
