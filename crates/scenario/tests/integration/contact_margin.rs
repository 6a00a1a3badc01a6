//! The scenario's `contact_margin_cm` reaches the step's contact detector; a margin that is
//! not a positive length is refused with its name.

use hagfish_scenario::{LoadedScenario, Override};

fn data(path: &str) -> String {
    format!("{}/../../data/{path}", env!("CARGO_MANIFEST_DIR"))
}

fn margin_of(path: &str, sets: &[&str]) -> Result<f64, String> {
    let overrides: Vec<Override> = sets
        .iter()
        .map(|s| Override::parse(s).map_err(|e| e.to_string()))
        .collect::<Result<_, _>>()?;
    let loaded = LoadedScenario::load_with(data(path), &overrides).map_err(|e| e.to_string())?;
    let (world, _) = loaded.build().map_err(|e| e.to_string())?;
    Ok(world.options().contact.margin)
}

#[test]
fn the_margin_is_the_files_or_the_default() {
    // Choi et al.'s thin rod sets its own; the hagfish scenarios keep the default 0.1 cm.
    assert_eq!(margin_of("validation/overhand_pull.ron", &[]), Ok(0.04));
    assert_eq!(margin_of("scenarios/form.ron", &[]), Ok(0.1));
    assert_eq!(margin_of("scenarios/form.ron", &["contact_margin_cm=0.03"]), Ok(0.03));
}

#[test]
fn a_margin_that_is_not_a_positive_length_is_refused_by_name() {
    for bad in ["0.0", "-0.1"] {
        let set = format!("contact_margin_cm={bad}");
        let error = margin_of("scenarios/form.ron", &[&set]).expect_err(&set);
        assert!(error.contains("contact_margin_cm"), "{set}: {error}");
    }
}
