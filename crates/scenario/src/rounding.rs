//! Rounding perturbations of a run: the knot runs are chaotic (a change of the time step by a
//! few parts in 10¹² moves the knot by centimetres within seconds, docs/physics.md), so a
//! claim is judged over replicates that differ only at rounding level, like the same run on
//! another CPU. Replicate `j` runs with the time step h(1 + j·10⁻¹²); `j = 0` is the run as
//! written. The time step is perturbed rather than the initial shape because it needs no new
//! scenario field, moves the rounding of every step from the first one, and is what the tests
//! and `cargo xtask family --rounding` judge claims by.

/// The relative change of the time step between successive replicates.
pub const ROUNDING_STEP: f64 = 1e-12;

/// The time step (s) of replicate `j` of a run whose time step is `time_step_s`:
/// h(1 + j·[`ROUNDING_STEP`]).
pub fn rounding_perturbed_step(time_step_s: f64, j: usize) -> f64 {
    time_step_s * (1.0 + j as f64 * ROUNDING_STEP)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replicate_zero_is_the_run_as_written_and_the_others_differ_at_rounding_level() {
        assert_eq!(rounding_perturbed_step(0.01, 0).to_bits(), 0.01_f64.to_bits());
        let (one, two) = (rounding_perturbed_step(0.01, 1), rounding_perturbed_step(0.01, 2));
        assert!(one > 0.01 && two > one);
        assert!((two / 0.01 - 1.0 - 2e-12).abs() < 1e-15);
    }
}
