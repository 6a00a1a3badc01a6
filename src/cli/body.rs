//! `hagfish body FILE`: loads a body file (hagfish biometrics or a rod) and prints the derived
//! chain (D5–D8): a header with the totals and the joint springs (derived from a rod's
//! stiffnesses, or a hagfish's scaled to its body count, D16), the skin if the body has one, and
//! one
//! row per body (index, s/L of its centre, radius, mass, joint type, limits per DOF in
//! degrees).

use std::io::Write;
use std::path::PathBuf;

use hagfish_anatomy::{Body, BodyRow, BodyTable};

use super::CliError;

/// Arguments of `hagfish body`.
#[derive(Debug, clap::Args)]
pub struct BodyArgs {
    /// Body RON file: hagfish biometrics (data/hagfish/es103.ron) or a rod (data/rods/thin.ron).
    file: PathBuf,
}

/// Loads, validates and derives the table, then writes header and rows to `out`. The model
/// itself is built too, so that a file this command accepts also yields a valid tree.
pub fn run(args: &BodyArgs, out: &mut impl Write) -> Result<(), CliError> {
    let body = Body::load(&args.file)?;
    let table = body.body_table()?;
    let model = body.to_model()?;
    let label = match body {
        Body::Hagfish(_) => "specimen",
        Body::Rod(_) => "rod     ",
    };
    writeln!(out, "{label}  {} ({})", body.name(), args.file.display())?;
    writeln!(
        out,
        "length    {} cm = {} bodies x {:.6} cm",
        body.length_cm(),
        table.rows.len(),
        table.segment_length_cm
    )?;
    writeln!(out, "mass      {} g (sum over bodies {:.9} g)", body.mass_g(), table.total_mass_g())?;
    match &body {
        Body::Rod(rod) => writeln!(
            out,
            "springs   bend {:.6} dyn*cm/rad = B/(2l), twist {:.6} dyn*cm/rad = C/(2l), damping {:.6} dyn*cm*s/rad",
            rod.bend_spring_dyn_cm_per_rad(),
            rod.twist_spring_dyn_cm_per_rad(),
            rod.joint_damping_dyn_cm_s_per_rad()
        )?,
        Body::Hagfish(fish) => writeln!(
            out,
            "springs   bend {:.6} dyn*cm/rad, twist {:.6} dyn*cm/rad, damping {:.6} dyn*cm*s/rad (the file's values x N/N_ref = {}/{})",
            fish.joint_bending_stiffness(),
            fish.joint_twist_stiffness(),
            fish.joint_damping(),
            fish.body_count,
            fish.reference_body_count
        )?,
    }
    writeln!(
        out,
        "density   {:.6} g/cm3 (volume {:.4} cm3)",
        table.density_g_per_cm3, table.volume_cm3
    )?;
    if let Body::Hagfish(hagfish_anatomy::Biometrics { skin: Some(skin), .. }) = &body {
        writeln!(
            out,
            "skin      {:.1} % of the radius over the core, pressure {} dyn/cm2 (docs/physics.md, Skin)",
            100.0 * skin.thickness_fraction,
            skin.pressure_dyn_per_cm2
        )?;
    }
    writeln!(out, "bodies    {}", model.body_count())?;
    writeln!(out, "DOFs      {}", model.dof_count())?;
    writeln!(out)?;
    write_rows(&table, out)
}

/// The per-body table, one line per body, fixed-width columns.
fn write_rows(table: &BodyTable, out: &mut impl Write) -> Result<(), CliError> {
    writeln!(
        out,
        "{:>5}  {:>6}  {:>9}  {:>8}  {:<9}  limits_deg",
        "index", "s/L", "radius_cm", "mass_g", "joint"
    )?;
    for row in &table.rows {
        writeln!(
            out,
            "{:>5}  {:>6.4}  {:>9.5}  {:>8.5}  {:<9}  {}",
            row.index,
            row.centre_fraction,
            row.radius_cm,
            row.mass_g,
            row.joint.name(),
            limits(row)
        )?;
    }
    Ok(())
}

/// `[lower, upper]` per DOF in degrees, space separated.
fn limits(row: &BodyRow) -> String {
    let ranges: Vec<String> =
        row.limits_deg.iter().map(|l| format!("[{:.2}, {:.2}]", l.lower, l.upper)).collect();
    ranges.join(" ")
}
