//! A legend in its own column beside a chart, so that it never hides data.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::draw_result::{DrawResult, failed};
use crate::font::FAMILY;
use crate::style::{LABEL_SIZE, LINE_WIDTH};

/// Width of a legend column, px.
pub(crate) const LEGEND_WIDTH: u32 = 200;

/// One legend entry: a line sample and its label.
pub(crate) struct LegendEntry {
    /// The label.
    pub label: String,
    /// Line colour.
    pub colour: RGBColor,
    /// Dashed sample rather than solid.
    pub dashed: bool,
    /// Line width, px.
    pub width: u32,
}

impl LegendEntry {
    /// A solid entry of the data line width.
    pub(crate) fn solid(label: impl Into<String>, colour: RGBColor) -> Self {
        Self {
            label: label.into(),
            colour,
            dashed: false,
            width: LINE_WIDTH,
        }
    }

    /// A dashed entry of width `width`.
    pub(crate) fn dashed(label: impl Into<String>, colour: RGBColor, width: u32) -> Self {
        Self {
            label: label.into(),
            colour,
            dashed: true,
            width,
        }
    }
}

/// Draws `entries` top-down in `area`, starting `top` px below its top.
pub(crate) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
    top: i32,
) -> DrawResult {
    let text =
        TextStyle::from((FAMILY, LABEL_SIZE).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    for (i, entry) in entries.iter().enumerate() {
        let y = top + 22 * i as i32;
        let style = entry.colour.stroke_width(entry.width);
        let segments: &[(i32, i32)] = if entry.dashed {
            &[(10, 17), (21, 28), (32, 39)]
        } else {
            &[(10, 39)]
        };
        for &(x0, x1) in segments {
            area.draw(&PathElement::new(vec![(x0, y), (x1, y)], style))
                .map_err(failed)?;
        }
        area.draw(&Text::new(entry.label.as_str(), (46, y), text.clone()))
            .map_err(failed)?;
    }
    Ok(())
}
