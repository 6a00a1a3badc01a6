//! `hagfish params`: every scenario parameter with its unit, default and meaning, from the
//! one table in `hagfish-sim` ([`hagfish_scenario::PARAMETERS`]).

use std::io::Write;

use hagfish_scenario::PARAMETERS;

use super::CliError;

/// Prints the table, one parameter per line, in aligned columns.
pub fn run(out: &mut impl Write) -> Result<(), CliError> {
    let width = |f: fn(&hagfish_scenario::Parameter) -> &str| {
        PARAMETERS.iter().map(|p| f(p).chars().count()).max().unwrap_or(0)
    };
    let (name, unit, default) = (width(|p| p.name), width(|p| p.unit), width(|p| p.default));
    writeln!(out, "{:name$}  {:unit$}  {:default$}  meaning", "name", "unit", "default")?;
    for p in PARAMETERS {
        writeln!(out, "{:name$}  {:unit$}  {:default$}  {}", p.name, p.unit, p.default, p.meaning)?;
    }
    Ok(())
}
