//! The runs of `cargo xtask family`: each member of the family, and with `--rounding N` each
//! at N − 1 rounding perturbations of its time step, h(1 + j·10⁻¹²), j = 1 … N − 1 — the knot
//! runs are chaotic, so a claim is judged over such replicates, not one trajectory.

use std::path::PathBuf;

use hagfish_bench_support::Variant;
use hagfish_scenario::rounding_perturbed_step;

use crate::family::Runner;

/// One run: a member at one rounding perturbation `j` of its time step, with its body file
/// (written once per member, before any of its runs reads it).
pub struct Case<'a> {
    /// The member.
    pub variant: &'a Variant,
    /// Its body file, or why it could not be written.
    pub body: &'a Result<PathBuf, String>,
    /// The perturbation: δh/h = j·10⁻¹² (0: the member as written).
    pub j: usize,
}

impl Case<'_> {
    /// The row label: the member's name, and δh/h when perturbed.
    pub fn label(&self) -> String {
        match self.j {
            0 => self.variant.name.into(),
            j => format!("{} δh/h {j}e-12", self.variant.name),
        }
    }

    /// Runs this case into `<work>/<name>` (`<name>_dh<j>` when perturbed) with the `extra`
    /// overrides; `scenario_step` is the scenario's time step (s), the base of a member that
    /// sets none. The run directory, or what stopped the run.
    pub fn run(
        &self,
        runner: &Runner<'_>,
        scenario_step: f64,
        extra: &[String],
    ) -> Result<PathBuf, String> {
        let body = self.body.as_ref().map_err(Clone::clone)?;
        let mut extra = extra.to_vec();
        let suffix = match self.j {
            0 => String::new(),
            j => {
                let step = member_step(self.variant, runner.request.sets, scenario_step)?;
                let perturbed = rounding_perturbed_step(step, j);
                extra.push(format!("time_step_s={perturbed:?}"));
                format!("_dh{j}")
            }
        };
        runner.run(self.variant, body, &suffix, &extra)
    }
}

/// Every member's cases, in the members' order: j = 0 … `rounding` − 1 for each.
pub fn cases<'a>(
    members: &'a [Variant],
    bodies: &'a [Result<PathBuf, String>],
    rounding: usize,
) -> Vec<Case<'a>> {
    members
        .iter()
        .zip(bodies)
        .flat_map(|(variant, body)| (0..rounding.max(1)).map(move |j| Case { variant, body, j }))
        .collect()
}

/// The time step of `variant`'s runs: the last `time_step_s=` of its own and the request's
/// overrides, else the scenario's.
fn member_step(variant: &Variant, sets: &[String], scenario_step: f64) -> Result<f64, String> {
    let set = variant.sets.iter().copied().chain(sets.iter().map(String::as_str));
    match set.filter_map(|s| s.strip_prefix("time_step_s=")).next_back() {
        Some(value) => value.trim().parse().map_err(|e| format!("time_step_s={value}: {e}")),
        None => Ok(scenario_step),
    }
}
