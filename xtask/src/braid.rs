//! `cargo xtask braid`: the frictionless loose trefoil settled at one pull, for a peer to settle
//! the same knot (`bench/peers/audoly_braid.py`; docs/validation.md, "Loose trefoil with
//! friction"). On a rod of radius h and bending stiffness B pulled by F it prints the braid's
//! total normal force N and its number N h²/(σBε³) with ε = (2Fh²/B)^¼ (Audoly et al.'s
//! frictionless law F h²/B = ε⁴/2 solved for ε; their σ = 0.492 is the number's 1 at leading
//! order), the loop radius where its tangent is ⊥ the pull beside the law's √(B/(2F)), and with
//! `--export` writes them with the rod and its settled centreline as JSON.

use std::path::Path;

use hagfish_validation::frictional_knot::{self, normal_force_number};
use hagfish_validation::loose_knot::Refinement;
use serde::Serialize;

/// What to settle.
pub struct Request<'a> {
    /// The rod's radius h (cm).
    pub rod_radius_cm: f64,
    /// The pull F (dyn).
    pub tension_dyn: f64,
    /// Bodies and time step, where not the shipped ones.
    pub resolution: Refinement,
    /// Where to write the JSON.
    pub export: Option<&'a Path>,
}

/// The rod as the loose-trefoil scenario built it (CGS).
#[derive(Serialize)]
struct RodExport {
    length_cm: f64,
    radius_cm: f64,
    bodies: usize,
    density_g_per_cm3: f64,
    bending_stiffness_dyn_cm2: f64,
    twist_stiffness_dyn_cm2: f64,
}

/// The settled knot: what `--export` writes.
#[derive(Serialize)]
struct BraidExport {
    source: String,
    rod: RodExport,
    tension_dyn: f64,
    /// ε = (2Fh²/B)^¼.
    epsilon: f64,
    normal_force_dyn: f64,
    /// N h²/(σBε³).
    normal_force_number: f64,
    loop_radius_cm: f64,
    /// √(B/(2F)): the loop radius the first integral gives a frictionless knot exactly.
    law_loop_radius_cm: f64,
    self_contacts: usize,
    /// The bodies' ends from the head (bodies + 1 points, cm).
    centreline_cm: Vec<[f64; 3]>,
}

/// Settles the knot, prints its one-line summary and writes the export.
pub fn run(root: &Path, request: &Request<'_>) -> Result<(), String> {
    let resolution =
        Refinement { rod_radius_cm: Some(request.rod_radius_cm), ..request.resolution };
    let (knot, settled) =
        frictional_knot::frictionless_settled(root, request.tension_dyn, resolution)
            .map_err(|e| e.to_string())?;
    let rod = &settled.rod;
    let (h, b, f) = (rod.radius_cm, rod.bending_stiffness_dyn_cm2, request.tension_dyn);
    let epsilon = (2.0 * f * h * h / b).powf(0.25);
    let export = BraidExport {
        source: format!(
            "cargo xtask braid --radius {h} --force {f} --bodies {} --time-step {}",
            rod.body_count,
            settled.world.options().time_step
        ),
        rod: RodExport {
            length_cm: rod.length_cm,
            radius_cm: h,
            bodies: rod.body_count,
            density_g_per_cm3: rod.density_g_per_cm3,
            bending_stiffness_dyn_cm2: b,
            twist_stiffness_dyn_cm2: rod.twist_stiffness_dyn_cm2,
        },
        tension_dyn: f,
        epsilon,
        normal_force_dyn: knot.contact_normal_force_dyn,
        normal_force_number: normal_force_number(knot.contact_normal_force_dyn, (h, b), epsilon),
        loop_radius_cm: knot.loop_radius_cm(),
        law_loop_radius_cm: (b / (2.0 * f)).sqrt(),
        self_contacts: settled.world.data().self_contacts.len(),
        centreline_cm: settled.body_ends().iter().map(|p| p.to_array()).collect(),
    };
    println!("{}", summary(&export));
    if let Some(path) = request.export {
        let json = serde_json::to_string(&export).map_err(|e| e.to_string())?;
        std::fs::write(path, json).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    Ok(())
}

/// The settled knot in one line.
fn summary(export: &BraidExport) -> String {
    format!(
        "h = {} cm, F = {} dyn, ε = {:.4}: N = {:.3} dyn, N h²/(σBε³) = {:.4}; loop radius {:.4} cm \
         (law {:.4}); {} self contacts",
        export.rod.radius_cm,
        export.tension_dyn,
        export.epsilon,
        export.normal_force_dyn,
        export.normal_force_number,
        export.loop_radius_cm,
        export.law_loop_radius_cm,
        export.self_contacts
    )
}
