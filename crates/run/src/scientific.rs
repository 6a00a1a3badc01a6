//! `{:.6e}` formatting of the generalized forces in `forces.csv`, where most values are exact
//! zeros (every limit force while no joint is at a limit, thigmotaxis tail-ward of the knot):
//! those are written as the text the float formatter would give, without running it.

use std::fmt;

/// A value written as `{:.6e}` would write it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Scientific(pub(crate) f64);

impl fmt::Display for Scientific {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.0 {
            0.0 if self.0.is_sign_negative() => f.write_str("-0.000000e0"),
            0.0 => f.write_str("0.000000e0"),
            value => write!(f, "{value:.6e}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_what_the_float_formatter_writes() {
        for value in [0.0, -0.0, 1.0, -2.5e-300, 123_456.789, f64::MAX, f64::NAN, f64::INFINITY] {
            assert_eq!(Scientific(value).to_string(), format!("{value:.6e}"));
        }
    }
}
