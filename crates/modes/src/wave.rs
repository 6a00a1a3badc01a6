//! The travelling-wave test of the dominant pair of modes, in the manner of complex
//! orthogonal decomposition: modes 1 and 2 read as one complex wave.

use crate::error::ModesError;
use crate::field::Field;
use crate::line_fit::{LineFit, fit_line, unwrap};
use crate::pod::Pod;

/// The fraction of max |φ| below which a DOF is left out of the spatial phase fit (where the
/// pair's amplitude is small its phase is noise).
pub const AMPLITUDE_THRESHOLD: f64 = 0.1;

/// Modes 1 and 2 as one wave. With φ(s) = v₁(s) + i v₂(s) = |φ| e^{iθ(s)} and
/// a(t) = a₁(t) + i a₂(t) = |a| e^{iψ(t)}, the pair is a₁v₁ + a₂v₂ = |a||φ| cos(θ(s) − ψ(t)):
/// a wave whose crests move at ds/dt = ω/k with k = dθ/ds and ω = dψ/dt. θ is unwrapped
/// along s over the DOFs with |φ| ≥ [`AMPLITUDE_THRESHOLD`]·max|φ|, ψ over the frames; k and ω
/// are least-squares slopes, and their R² says whether the pair is a wave at all (a standing
/// pattern or noise gives a low R²). The knot's speed is the least-squares slope of the
/// field's knot position against time over the frames that have one.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct WaveFit {
    /// θ(s) against s: slope k (rad/cm).
    pub spatial: LineFit,
    /// ψ(t) against t: slope ω (rad/s).
    pub temporal: LineFit,
    /// c = ω / k (cm/s; > 0 tail-ward).
    pub phase_speed_cm_s: f64,
    /// The knot position against time: slope = the knot's speed (cm/s), if ≥ 2 frames had one.
    pub knot: Option<LineFit>,
    /// c divided by the knot's speed (`None` without a knot speed or when it is 0).
    pub speed_ratio: Option<f64>,
}

impl WaveFit {
    /// The fit of `pod`'s first two modes on `field`'s arc lengths and times.
    pub fn of(pod: &Pod, field: &Field) -> Result<Self, ModesError> {
        if pod.modes() < 2 {
            return Err(ModesError::Invalid(format!(
                "{}: the travelling-wave test needs two modes, the field has {}",
                field.label,
                pod.modes()
            )));
        }
        let (v1, v2) = (&pod.shapes[0], &pod.shapes[1]);
        let magnitude: Vec<f64> = v1.iter().zip(v2).map(|(a, b)| a.hypot(*b)).collect();
        let largest = magnitude.iter().copied().fold(0.0, f64::max);
        let mut order: Vec<usize> =
            (0..v1.len()).filter(|&d| magnitude[d] >= AMPLITUDE_THRESHOLD * largest).collect();
        order.sort_by(|&a, &b| field.arcs_cm[a].total_cmp(&field.arcs_cm[b]));
        let theta: Vec<f64> = order.iter().map(|&d| v2[d].atan2(v1[d])).collect();
        let arcs: Vec<f64> = order.iter().map(|&d| field.arcs_cm[d]).collect();
        let (a1, a2) = (&pod.time_courses[0], &pod.time_courses[1]);
        let psi: Vec<f64> = a1.iter().zip(a2).map(|(x, y)| y.atan2(*x)).collect();
        let unfit = |what: &str| {
            ModesError::Invalid(format!("{}: no line through the {what} phase", field.label))
        };
        let spatial = fit_line(&arcs, &unwrap(&theta)).ok_or_else(|| unfit("spatial"))?;
        let temporal = fit_line(&field.times, &unwrap(&psi)).ok_or_else(|| unfit("temporal"))?;
        let phase_speed_cm_s = temporal.slope / spatial.slope;
        let (times, knot): (Vec<f64>, Vec<f64>) =
            field.times.iter().zip(&field.knot_cm).filter_map(|(t, k)| Some((*t, (*k)?))).unzip();
        let knot = fit_line(&times, &knot);
        let speed_ratio = knot.filter(|k| k.slope != 0.0).map(|k| phase_speed_cm_s / k.slope);
        Ok(Self { spatial, temporal, phase_speed_cm_s, knot, speed_ratio })
    }
}
