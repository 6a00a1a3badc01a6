//! `cargo xtask validate`: every check of `hagfish-validation` as the Markdown table of
//! `docs/validation.md`, with the date and the wall time; false if one fails.

use std::path::Path;
use std::time::Instant;

/// Runs the checks and prints the table; `Ok(false)` if a check is out of tolerance.
pub fn run(root: &Path) -> Result<bool, String> {
    let clock = Instant::now();
    let checks = hagfish_validation::all_checks(root).map_err(|e| e.to_string())?;
    println!("| check | set-up | formula | source | expected | measured | error | tolerance |");
    println!("|---|---|---|---|---|---|---|---|");
    for check in &checks {
        println!("{}", check.markdown_row());
    }
    let failed: Vec<&str> =
        checks.iter().filter(|c| !c.passes()).map(|c| c.name.as_str()).collect();
    println!();
    println!(
        "{} checks in {:.1} s; failed: {}",
        checks.len(),
        clock.elapsed().as_secs_f64(),
        if failed.is_empty() { "none".to_string() } else { failed.join(", ") }
    );
    Ok(failed.is_empty())
}
