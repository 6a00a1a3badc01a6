//! `hagfish body FILE` run as a process: the real ES103 file gives the header totals and 100
//! rows; broken files give one `file:line:column` message on stderr and exit code 2.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const ES103: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/data/hagfish/es103.ron");

fn hagfish_body(file: &Path) -> Output {
    match Command::new(env!("CARGO_BIN_EXE_hagfish")).arg("body").arg(file).output() {
        Ok(output) => output,
        Err(e) => panic!("cannot run hagfish: {e}"),
    }
}

/// The value after `key` on the header line that starts with `key`.
fn header<'a>(stdout: &'a str, key: &str) -> &'a str {
    let line = stdout.lines().find(|l| l.starts_with(key));
    line.and_then(|l| l[key.len()..].split_whitespace().next())
        .unwrap_or_else(|| panic!("no header {key:?} in\n{stdout}"))
}

/// Writes ES103 with `from` replaced by `to` into the test's temporary directory and
/// returns the path and the 1-based line and column of `at` in the written text (its first
/// occurrence on a line that is not a comment).
fn broken_copy(name: &str, from: &str, to: &str, at: &str) -> (PathBuf, usize, usize) {
    let text = std::fs::read_to_string(ES103).unwrap_or_else(|e| panic!("{ES103}: {e}"));
    assert!(text.contains(from));
    let text = text.replacen(from, to, 1);
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("body_command");
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let path = dir.join(name);
    std::fs::write(&path, &text).unwrap_or_else(|e| panic!("{e}"));
    let (line, column) = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim_start().starts_with("//"))
        .find_map(|(i, l)| l.find(at).map(|byte| (i + 1, 1 + l[..byte].chars().count())))
        .unwrap_or_else(|| panic!("{at:?} not found"));
    (path, line, column)
}

/// Asserts exit code 2, empty stdout and one stderr line `error: <path>:<line>:<col>: …`
/// containing `words`.
fn assert_fails_at(output: &Output, path: &Path, line: usize, column: usize, words: &[&str]) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(output.stdout.is_empty());
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    let prefix = format!("error: {}:{line}:{column}: ", path.display());
    assert!(stderr.starts_with(&prefix), "{stderr:?} does not start with {prefix:?}");
    for w in words {
        assert!(stderr.contains(w), "{stderr:?} lacks {w:?}");
    }
    assert!(!stderr.contains("panicked"));
}

#[test]
fn es103_prints_header_totals_and_100_rows() {
    let output = hagfish_body(Path::new(ES103));
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(header(&stdout, "specimen"), "ES103");
    assert_eq!(header(&stdout, "length"), "42.4");
    assert_eq!(header(&stdout, "mass"), "80");
    assert_eq!(header(&stdout, "bodies"), "100");
    assert_eq!(header(&stdout, "DOFs"), "150");
    let density: f64 = header(&stdout, "density").parse().unwrap_or(f64::NAN);
    assert!((density - 0.871).abs() < 0.002, "{density}");

    let rows: Vec<Vec<&str>> = stdout
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .filter(|cols| cols.first().is_some_and(|c| c.parse::<usize>().is_ok()))
        .collect();
    assert_eq!(rows.len(), 100);
    let mut mass = 0.0;
    for (i, cols) in rows.iter().enumerate() {
        assert_eq!(cols[0], i.to_string());
        mass += cols[3].parse::<f64>().unwrap_or(f64::NAN);
        let (joint, limit_columns) = if i % 2 == 0 { ("revolute", 2) } else { ("universal", 4) };
        assert_eq!(cols[4], joint);
        assert_eq!(cols.len(), 5 + limit_columns);
    }
    assert!((mass - 80.0).abs() < 1e-3, "Σ mass column = {mass}");
}

#[test]
fn ron_syntax_error_exits_2_with_line_and_column() {
    let (path, line, column) =
        broken_copy("syntax.ron", "length_cm: 42.4,", "length_cm: 42.4", "mass_g");
    let output = hagfish_body(&path);
    assert_fails_at(&output, &path, line, column, &["comma"]);
}

#[test]
fn invalid_value_exits_2_naming_the_field() {
    let (path, line, column) =
        broken_copy("negative_mass.ron", "mass_g: 80.0", "mass_g: -80.0", "-80.0");
    let output = hagfish_body(&path);
    assert_fails_at(&output, &path, line, column, &["mass_g", "-80"]);
}

#[test]
fn missing_file_exits_2_with_the_path() {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("no_such_file.ron");
    let output = hagfish_body(&path);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(stderr.starts_with(&format!("error: {}: ", path.display())), "{stderr}");
}

const THIN_ROD: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/data/rods/thin.ron");

#[test]
fn a_rod_prints_its_derived_springs_and_one_row_per_body() {
    let output = hagfish_body(Path::new(THIN_ROD));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(header(&stdout, "rod"), "thin");
    assert_eq!(header(&stdout, "springs"), "bend");
    assert!(stdout.contains("2454.500000 dyn*cm/rad = B/(2l)"), "B/(2ℓ) = 490.9/0.2:\n{stdout}");
    assert_eq!(header(&stdout, "bodies"), "100");
}

#[test]
fn bad_rod_values_are_exit_2_at_their_line_and_column() {
    let text = std::fs::read_to_string(THIN_ROD).unwrap_or_else(|e| panic!("{THIN_ROD}: {e}"));
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("body_command");
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    for (name, from, to, words) in [
        (
            "b_zero.ron",
            "bending_stiffness_dyn_cm2: 490.9",
            "bending_stiffness_dyn_cm2: 0.0",
            &["bending_stiffness_dyn_cm2", "> 0"][..],
        ),
        (
            "b_nan.ron",
            "bending_stiffness_dyn_cm2: 490.9",
            "bending_stiffness_dyn_cm2: NaN",
            &["bending_stiffness_dyn_cm2"][..],
        ),
        ("thick.ron", "radius_cm: 0.05", "radius_cm: 1.5", &["radius_cm", "10 body lengths"][..]),
        ("odd.ron", "body_count: 100", "body_count: 99", &["body_count", "even"][..]),
    ] {
        assert!(text.contains(from), "{from}");
        let broken = text.replacen(from, to, 1);
        let path = dir.join(name);
        std::fs::write(&path, &broken).unwrap_or_else(|e| panic!("{e}"));
        let value = to.split(": ").nth(1).unwrap_or_default();
        let (line, column) = broken
            .lines()
            .enumerate()
            .find_map(|(i, l)| {
                (l.contains(to))
                    .then(|| (i + 1, 1 + l[..l.find(value).unwrap_or(0)].chars().count()))
            })
            .unwrap_or_else(|| panic!("{to:?} not found"));
        assert_fails_at(&hagfish_body(&path), &path, line, column, words);
    }
}

/// A body file with a skin shows it in the header; ES103 (without one) does not.
#[test]
fn a_skin_is_shown_in_the_header() {
    let (path, _, _) = broken_copy(
        "skinned.ron",
        "tail_taper: None,",
        "tail_taper: None,\n    skin: Some((thickness_fraction: 0.25, pressure_dyn_per_cm2: 1000.0)),",
        "skin",
    );
    let output = hagfish_body(&path);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(0), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(header(&stdout, "skin"), "25.0");
    let plain = hagfish_body(Path::new(ES103));
    assert!(!String::from_utf8_lossy(&plain.stdout).lines().any(|l| l.starts_with("skin")));
}
