//! A modal force space's spec is checked at load, each error at its `file:line:column`: a
//! missing file, more modes than the file has, an unknown kind, k = 0, and shapes that are
//! rank-deficient on the body; a good spec resolves to an orthonormal basis of k columns.

use std::path::{Path, PathBuf};

use hagfish_control::{ForceSpace, Phase};
use hagfish_scenario::LoadedScenario;

const THESIS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/scenarios/thesis.ron");

/// A `modes.csv` of kind `bend` with two modes, sampled on the Y and Z axes at three s/L, the
/// second mode twice the first when `dependent`.
fn modes_file(name: &str, dependent: bool) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hagfish-modal-spec-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temporary directory");
    let mut text = String::from("kind,mode,axis,s_cm,s_L,shape\n");
    for (mode, scale) in [(1, 1.0), (2, 2.0)] {
        for (i, s_l) in [0.0, 0.5, 1.0].into_iter().enumerate() {
            for axis in ['Y', 'Z'] {
                let v = if dependent || mode == 1 { scale * (1.0 + s_l) } else { i as f64 - 1.0 };
                text.push_str(&format!("bend,{mode},{axis},{},{s_l},{v}\n", s_l * 50.0));
            }
        }
    }
    let path = dir.join(name);
    std::fs::write(&path, text).expect("modes.csv written");
    path
}

/// thesis.ron with its slide phase confined to `space` (RON text), as if it sat where
/// thesis.ron does.
fn load_with_space(space: &str) -> Result<LoadedScenario, String> {
    let text = std::fs::read_to_string(THESIS).expect("thesis.ron");
    let (head, slide) = text.split_once("name: \"slide\"").expect("a slide phase");
    let slide = slide.replacen(
        "max_force_dyn: 2000.0,",
        &format!("max_force_dyn: 2000.0, force_space: {space},"),
        1,
    );
    let text = format!("{head}name: \"slide\"{slide}");
    LoadedScenario::parse(text.as_bytes(), Path::new(THESIS)).map_err(|e| e.to_string())
}

/// `file:line:column:` at the start of `message`, in thesis.ron, on the line of `key`.
fn assert_positioned(message: &str, key: &str) {
    let (line, column) = message
        .strip_prefix(THESIS)
        .and_then(|rest| rest.split(':').nth(1).zip(rest.split(':').nth(2)))
        .and_then(|(l, c)| l.parse::<usize>().ok().zip(c.parse::<usize>().ok()))
        .unwrap_or_else(|| panic!("no position: {message}"));
    let text = std::fs::read_to_string(THESIS).expect("thesis.ron");
    let slide_line = text.lines().position(|l| l.contains("name: \"slide\"")).expect("slide");
    assert!(line > slide_line && column > 0, "{key} at {line}:{column}: {message}");
}

#[test]
fn a_good_spec_resolves_to_k_orthonormal_columns_and_bad_specs_are_positioned_errors() {
    let good = modes_file("good.csv", false);
    let loaded = load_with_space(&format!("Modes((file: {good:?}, kind: \"bend\", modes: 2))"))
        .expect("a good spec loads");
    let Some(Phase::Thigmotaxis(slide)) = loaded.scenario.phases.last() else { panic!("slide") };
    let ForceSpace::Modes(space) = &slide.parameters.force_space else { panic!("modal") };
    let basis = space.basis.as_ref().expect("resolved at load");
    assert_eq!(basis.modes(), 2);
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    assert!((dot(basis.column(0), basis.column(0)) - 1.0).abs() < 1e-12);
    assert!(dot(basis.column(0), basis.column(1)).abs() < 1e-12);
    let twist = hagfish_sim::rows::twist_dofs(&loaded.body.to_model().expect("model"));
    assert!(twist.iter().all(|&d| basis.column(0)[d] == 0.0), "bend: no twist entries");

    let dependent = modes_file("dependent.csv", true);
    let space = |file: &Path, kind: &str, modes: u32| {
        format!("Modes((file: {file:?}, kind: {kind:?}, modes: {modes}))")
    };
    let refused: [(String, &[&str], &str); 6] = [
        (space(Path::new("no/such/modes.csv"), "all", 1), &["no/such/modes.csv"], "file"),
        (space(&good, "bend", 3), &["k = 3", "2 modes"], "modes"),
        (space(&good, "all", 1), &["no modes of kind all"], "file"),
        (space(&good, "bendy", 1), &["bendy", "bend-y"], "kind"),
        (space(&good, "bend", 0), &["at least 1 mode"], "modes"),
        (space(&dependent, "bend", 2), &["mode 2", "not a basis"], "modes"),
    ];
    for (space, words, field) in refused {
        let error = load_with_space(&space).expect_err(&space);
        assert!(words.iter().all(|w| error.contains(w)), "{space}: {error}");
        assert_positioned(&error, field);
    }
}
