//! Embedded font for all figures.
//!
//! plotters is built with the `ab_glyph` text backend, which never looks at
//! system fonts: every family it draws with has to be registered by hand.
//! Shipping DejaVu Sans inside the binary makes the figures independent of
//! the machine they are rendered on, and DejaVu covers the Greek letters
//! (Γ, Δ, θ) and superscript digits used in labels and tick marks.

use std::sync::OnceLock;

use plotters::style::{register_font, FontStyle};

/// Family name under which the embedded font is registered. plotters falls
/// back to this name for its own default text (e.g. legends), so using it
/// keeps every piece of text on the same face.
pub const FONT_FAMILY: &str = "sans-serif";

/// The DejaVu Sans TrueType file, embedded at compile time.
static DEJAVU_SANS: &[u8] = include_bytes!("../../../../assets/fonts/DejaVuSans.ttf");

/// Registers the embedded font with plotters under [`FONT_FAMILY`].
///
/// Safe to call any number of times from any thread; the registration
/// itself runs once. Registration can only fail if the embedded bytes are not
/// a valid font, which would be a build defect rather than a runtime
/// condition; the outcome is remembered and text rendering would then report
/// a font error through the normal `Result` path instead of panicking here.
pub fn ensure_font_registered() {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    REGISTERED.get_or_init(|| {
        // Only the normal style is embedded; plotters falls back to it for
        // bold/italic requests under the same family name.
        register_font(FONT_FAMILY, FontStyle::Normal, DEJAVU_SANS).is_ok()
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_font_parses_and_registration_is_idempotent() {
        assert!(register_font(FONT_FAMILY, FontStyle::Normal, DEJAVU_SANS).is_ok());
        ensure_font_registered();
        ensure_font_registered();
    }
}
