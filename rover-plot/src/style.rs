//! The look shared by every figure: colours, font sizes, line widths.

use plotters::style::RGBColor;

/// Line colours, one per wheel (cycled past ten): a colour-blind-friendly
/// qualitative palette.
pub(crate) const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// The colour of wheel `j` (0-based).
pub(crate) fn wheel_colour(j: usize) -> RGBColor {
    PALETTE[j % PALETTE.len()]
}

/// A lighter shade of `colour` (halfway to white): contact-point paths,
/// drawn thin beside their wheel centre's path.
pub(crate) fn tint(colour: RGBColor) -> RGBColor {
    let half_to_white = |c: u8| c + (255 - c) / 2;
    RGBColor(
        half_to_white(colour.0),
        half_to_white(colour.1),
        half_to_white(colour.2),
    )
}

/// Colour of the body (G) path and of set-points.
pub(crate) const BODY: RGBColor = RGBColor(0, 0, 0);
/// Colour of the body outlines and of the settling marker.
pub(crate) const MARKER: RGBColor = RGBColor(110, 110, 110);

/// Figure title size, px.
pub(crate) const TITLE_SIZE: u32 = 22;
/// Panel caption size, px.
pub(crate) const CAPTION_SIZE: u32 = 16;
/// Axis description size, px.
pub(crate) const AXIS_DESC_SIZE: u32 = 14;
/// Tick label and legend size, px.
pub(crate) const LABEL_SIZE: u32 = 12;
/// Width of data lines, px.
pub(crate) const LINE_WIDTH: u32 = 2;
