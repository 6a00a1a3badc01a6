//! The inextensible elastica of a cantilever under a dead tip load, computed independently of
//! the simulator: `B θ'' = −P cos θ` on `0 ≤ s ≤ L` (θ the tangent's angle from the clamped
//! direction, the load perpendicular to it), `θ(0) = 0`, `θ'(L) = 0` (no moment at the free
//! end). In units of L with `α = PL²/B`: `θ'' = −α cos θ`. Solved by shooting on `θ'(0)`
//! (bisection on the sign of `θ'(1)`, RK4 with 4000 steps), the tip from
//! `x = ∫ cos θ`, `y = ∫ sin θ`.

/// The tip of the elastica in units of L, `(x, y)`, for the load `alpha = PL²/B` (> 0,
/// below the first shooting bracket's reach, α ≲ 20).
pub fn elastica_tip(alpha: f64) -> (f64, f64) {
    // θ'(0) = M(0)/B ∈ (0, α]: the root moment is at most PL.
    let (mut lo, mut hi) = (0.0, alpha);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        let (end_slope, _) = shoot(alpha, mid);
        // θ'(1) = θ'(0) − α∫cos θ: too small a root curvature leaves θ' < 0 at the free end.
        if end_slope < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    shoot(alpha, 0.5 * (lo + hi)).1
}

/// Integrates `(θ, θ', x, y)` from s = 0 to 1 with `θ'(0) = curvature`: returns `θ'(1)` and
/// the tip `(x, y)`.
fn shoot(alpha: f64, curvature: f64) -> (f64, (f64, f64)) {
    const STEPS: usize = 4000;
    let ds = 1.0 / STEPS as f64;
    let rate = |s: [f64; 4]| [s[1], -alpha * s[0].cos(), s[0].cos(), s[0].sin()];
    let mut state = [0.0, curvature, 0.0, 0.0];
    let along = |s: [f64; 4], k: [f64; 4], h: f64| std::array::from_fn(|i| s[i] + h * k[i]);
    for _ in 0..STEPS {
        let k1 = rate(state);
        let k2 = rate(along(state, k1, 0.5 * ds));
        let k3 = rate(along(state, k2, 0.5 * ds));
        let k4 = rate(along(state, k3, ds));
        state = std::array::from_fn(|i| {
            state[i] + ds / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
        });
    }
    (state[1], (state[2], state[3]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_loads_give_the_linear_deflection() {
        let alpha = 1e-3;
        let (x, y) = elastica_tip(alpha);
        assert!((y - alpha / 3.0).abs() < 1e-6 * alpha, "y = {y}, α/3 = {}", alpha / 3.0);
        assert!((1.0 - x) < 1e-6);
    }

    /// The inextensible tip stays within reach of the clamp and deflects less than the linear
    /// theory's α/3 (the load's moment arm shortens as the rod bends).
    #[test]
    fn large_loads_deflect_less_than_the_linear_theory_and_keep_the_length() {
        for alpha in [1.0, 3.0, 10.0] {
            let (x, y) = elastica_tip(alpha);
            assert!(y < alpha / 3.0, "α = {alpha}: y = {y}");
            assert!(x * x + y * y < 1.0, "α = {alpha}: the tip is within reach");
        }
    }
}
