//! The embedded font: DejaVu Sans, registered with plotters once per process.
//!
//! plotters is built without its `ttf` feature (which needs the system's
//! fontconfig); with `ab_glyph` it only knows the fonts registered here.

use std::sync::Once;

/// The font family name every text style of this crate uses.
pub(crate) const FAMILY: &str = "sans-serif";

static REGISTER: Once = Once::new();

/// Registers DejaVu Sans (regular and bold) as [`FAMILY`]; later calls do nothing.
///
/// The embedded fonts are valid TrueType files, so registration cannot fail
/// for a reason a user could fix; if it ever did, text drawing reports
/// `FontUnavailable` and [`crate::PlotError::Draw`] carries that message.
pub(crate) fn register_embedded_font() {
    use plotters::style::FontStyle;
    REGISTER.call_once(|| {
        let _ = plotters::style::register_font(FAMILY, FontStyle::Normal, dejavu::sans::regular());
        let _ = plotters::style::register_font(FAMILY, FontStyle::Bold, dejavu::sans::bold());
    });
}
