//! The plots' font: a subset of DejaVu Sans embedded in the binary (licence in
//! `assets/FONT-LICENSE.txt`), so text renders headless without system fonts.

use std::sync::OnceLock;

use plotters::style::FontStyle;

/// The family name the plots ask for.
pub const FAMILY: &str = "sans-serif";

const DEJAVU_SANS_SUBSET: &[u8] = include_bytes!("../assets/DejaVuSans-subset.ttf");

/// Registers the embedded font as [`FAMILY`] with plotters (once per process); `false` if
/// the font could not be parsed.
pub fn register() -> bool {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    *REGISTERED.get_or_init(|| {
        plotters::style::register_font(FAMILY, FontStyle::Normal, DEJAVU_SANS_SUBSET).is_ok()
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_embedded_font_registers() {
        assert!(super::register());
    }
}
