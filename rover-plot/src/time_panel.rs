//! One time-history panel: lines against time, the settling marker, a
//! legend when the lines have names. Every time plot is made of these.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::axis_range::{bounds, padded};
use crate::decimate::{MAX_POINTS, drop_flat, min_max};
use crate::draw_result::{DrawResult, failed};
use crate::font::FAMILY;
use crate::legend::{LEGEND_WIDTH, LegendEntry, draw_legend};
use crate::style::{AXIS_DESC_SIZE, CAPTION_SIZE, LABEL_SIZE, LINE_WIDTH, MARKER};
use crate::tick_label::tick_label;

/// One line of a panel.
pub(crate) struct Line<'a> {
    /// Legend entry; `None` for a panel's only line.
    pub label: Option<String>,
    /// Line colour.
    pub colour: RGBColor,
    /// Dashed (set-points) rather than solid.
    pub dashed: bool,
    /// Time, s.
    pub t: &'a [f64],
    /// Values, in the unit of the panel's axis.
    pub values: Vec<f64>,
}

/// A panel: a caption, the value axis' description, its lines.
pub(crate) struct TimePanel<'a> {
    /// Caption above the panel.
    pub caption: String,
    /// Value axis description with its unit, e.g. `Z \[m\]`.
    pub y_desc: String,
    /// The lines.
    pub lines: Vec<Line<'a>>,
}

/// Draws `panel` on `area` over the time range `t_axis`, with a dashed
/// vertical marker at `settle` when given.
pub(crate) fn draw_time_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &TimePanel<'_>,
    t_axis: Range<f64>,
    settle: Option<f64>,
) -> DrawResult {
    let (lo, hi) = bounds(panel.lines.iter().flat_map(|l| l.values.iter())).unwrap_or((0.0, 0.0));
    let y_axis = padded(lo, hi);
    let labelled = panel.lines.iter().any(|l| l.label.is_some());
    let (chart_area, legend_area) = if labelled {
        let (w, _) = area.dim_in_pixel();
        let (chart_area, legend_area) = area.split_horizontally(w.saturating_sub(LEGEND_WIDTH));
        (chart_area, Some(legend_area))
    } else {
        (area.clone(), None)
    };
    let mut builder = ChartBuilder::on(&chart_area);
    builder
        .margin(8)
        .x_label_area_size(40)
        .y_label_area_size(70);
    if !panel.caption.is_empty() {
        builder.caption(&panel.caption, (FAMILY, CAPTION_SIZE));
    }
    let mut chart = builder
        .build_cartesian_2d(t_axis, y_axis.clone())
        .map_err(failed)?;
    chart
        .configure_mesh()
        .x_desc("t [s]")
        .y_desc(panel.y_desc.as_str())
        .x_labels(6)
        .y_labels(5)
        .x_label_formatter(&tick_label)
        .y_label_formatter(&tick_label)
        .max_light_lines(4)
        .label_style((FAMILY, LABEL_SIZE))
        .axis_desc_style((FAMILY, AXIS_DESC_SIZE))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(205, 205, 205))
        .draw()
        .map_err(failed)?;

    if let Some(ts) = settle {
        let style = MARKER.stroke_width(1);
        chart
            .draw_series(DashedLineSeries::new(
                [(ts, y_axis.start), (ts, y_axis.end)],
                6,
                4,
                style,
            ))
            .map_err(failed)?;
        let text = TextStyle::from((FAMILY, LABEL_SIZE).into_font()).color(&MARKER);
        chart
            .draw_series(std::iter::once(
                EmptyElement::at((ts, y_axis.end)) + Text::new("settled", (4, 2), text),
            ))
            .map_err(failed)?;
    }

    let mut legend = Vec::new();
    for line in &panel.lines {
        let points = drop_flat(min_max(line.t, &line.values, MAX_POINTS));
        let style = line.colour.stroke_width(LINE_WIDTH);
        if line.dashed {
            chart
                .draw_series(DashedLineSeries::new(points, 8, 5, style))
                .map_err(failed)?;
        } else {
            chart
                .draw_series(LineSeries::new(points, style))
                .map_err(failed)?;
        }
        if let Some(label) = &line.label {
            legend.push(if line.dashed {
                LegendEntry::dashed(label.as_str(), line.colour, LINE_WIDTH)
            } else {
                LegendEntry::solid(label.as_str(), line.colour)
            });
        }
    }
    match legend_area {
        Some(legend_area) => draw_legend(&legend_area, &legend, 30),
        None => Ok(()),
    }
}
