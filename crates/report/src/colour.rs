//! Colour maps: a diverging one for signed values (blue – white – red, white at 0) and a
//! sequential one for arc length (viridis-like), both piecewise linear between stops.

/// An sRGB colour.
pub type Rgb = [u8; 3];

/// Blue → white → red (ColorBrewer RdBu, reversed), for t in [-1, 1]; 0 is white.
const DIVERGING: [Rgb; 7] = [
    [33, 102, 172],
    [103, 169, 207],
    [209, 229, 240],
    [247, 247, 247],
    [253, 219, 199],
    [239, 138, 98],
    [178, 24, 43],
];

/// Dark purple → blue → green → yellow (viridis at 6 stops), for t in [0, 1].
const SEQUENTIAL: [Rgb; 6] =
    [[68, 1, 84], [65, 68, 135], [42, 120, 142], [34, 168, 132], [122, 209, 81], [253, 231, 37]];

/// The diverging colour of `t` ∈ [-1, 1] (clamped; NaN is white).
pub fn diverging(t: f64) -> Rgb {
    let t = if t.is_nan() { 0.0 } else { t };
    interpolate(&DIVERGING, 0.5 * (t + 1.0))
}

/// The sequential colour of `t` ∈ [0, 1] (clamped; NaN is the first stop).
pub fn sequential(t: f64) -> Rgb {
    interpolate(&SEQUENTIAL, if t.is_nan() { 0.0 } else { t })
}

fn interpolate(stops: &[Rgb], t: f64) -> Rgb {
    let x = t.clamp(0.0, 1.0) * (stops.len() - 1) as f64;
    let i = (x.floor() as usize).min(stops.len() - 2);
    let w = x - i as f64;
    let (a, b) = (stops[i], stops[i + 1]);
    [0, 1, 2].map(|c| (f64::from(a[c]) * (1.0 - w) + f64::from(b[c]) * w).round() as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diverging_is_white_at_zero_blue_below_red_above_and_clamped() {
        assert_eq!(diverging(0.0), [247, 247, 247]);
        assert_eq!(diverging(f64::NAN), [247, 247, 247]);
        assert_eq!(diverging(-1.0), [33, 102, 172]);
        assert_eq!(diverging(1.0), [178, 24, 43]);
        assert_eq!(diverging(5.0), diverging(1.0));
        let (low, high) = (diverging(-0.5), diverging(0.5));
        assert!(low[2] > low[0] && high[0] > high[2]);
    }

    #[test]
    fn sequential_runs_from_the_first_to_the_last_stop() {
        assert_eq!(sequential(0.0), SEQUENTIAL[0]);
        assert_eq!(sequential(1.0), SEQUENTIAL[5]);
        assert_eq!(sequential(0.2), SEQUENTIAL[1]);
        assert_eq!(sequential(0.1), [67, 35, 110]);
    }
}
