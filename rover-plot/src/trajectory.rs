//! The trajectory projections (the paper's Figs. 8, 13, 16): the path of the
//! body's centre of mass G, of each wheel centre and of each contact point,
//! on the xz plane (side view) or the xy plane (top view), with equal scales
//! on both axes, a sketch of the body outline (convex hull of the wheel
//! centres, and G) at a few instants, and G's position at the end of settling.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::axis_range::{bounds, equal_scale};
use crate::convex_hull::convex_hull;
use crate::decimate::{MAX_PATH_POINTS, stride_indices};
use crate::draw_result::{DrawResult, failed};
use crate::font::FAMILY;
use crate::labels::Labels;
use crate::legend::{LEGEND_WIDTH, LegendEntry, draw_legend};
use crate::run_data::RunData;
use crate::style::{
    AXIS_DESC_SIZE, BODY, LABEL_SIZE, LINE_WIDTH, MARKER, TITLE_SIZE, tint, wheel_colour,
};
use crate::tick_label::tick_label;

/// Which plane the trajectories are projected on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Projection {
    /// Side view: X horizontal, Z vertical.
    Xz,
    /// Top view: X horizontal, Y vertical.
    Xy,
}

impl Projection {
    /// Indices (into X, Y, Z) of the horizontal and vertical axes.
    fn axes(self) -> (usize, usize) {
        match self {
            Projection::Xz => (0, 2),
            Projection::Xy => (0, 1),
        }
    }

    /// Caption words and axis descriptions.
    fn words(self) -> (&'static str, &'static str, &'static str) {
        match self {
            Projection::Xz => ("side view (xz plane)", "X [m]", "Z [m]"),
            Projection::Xy => ("top view (xy plane)", "X [m]", "Y [m]"),
        }
    }
}

/// Row indices at which the body outline is sketched: `count` instants evenly
/// spaced from the end of settling (or the start) to the end of the run.
fn outline_rows(t: &[f64], from: f64, count: usize) -> Vec<usize> {
    let end = t[t.len() - 1];
    let mut rows: Vec<usize> = (0..count)
        .map(|i| {
            let time = if count == 1 {
                end
            } else {
                from + (end - from) * i as f64 / (count - 1) as f64
            };
            nearest_row(t, time)
        })
        .collect();
    rows.dedup();
    rows
}

/// The row whose time is nearest to `time` (the earlier one on a tie); `t`
/// is non-empty and non-decreasing.
fn nearest_row(t: &[f64], time: f64) -> usize {
    let after = t.partition_point(|&s| s < time).min(t.len() - 1);
    if after > 0 && time - t[after - 1] <= t[after] - time {
        after - 1
    } else {
        after
    }
}

/// Draws the projection of the run's trajectories.
pub(crate) fn draw_trajectory<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    data: &RunData,
    labels: &Labels,
    projection: Projection,
) -> DrawResult {
    let (a, b) = projection.axes();
    let (view, x_desc, y_desc) = projection.words();
    root.fill(&WHITE).map_err(failed)?;
    let area = root
        .titled(&format!("{} — {view}", labels.title), (FAMILY, TITLE_SIZE))
        .map_err(failed)?;
    let (w, _) = area.dim_in_pixel();
    let (chart_area, legend_area) = area.split_horizontally(w.saturating_sub(LEGEND_WIDTH));

    // Every projected path: G, then per wheel its centre and its contact point.
    let mut paths: Vec<(&[f64], &[f64])> = vec![(&data.g[a], &data.g[b])];
    for wheel in &data.wheels {
        paths.push((&wheel.centre[a], &wheel.centre[b]));
        paths.push((&wheel.contact[a], &wheel.contact[b]));
    }
    let x_bounds = bounds(paths.iter().flat_map(|p| p.0.iter())).unwrap_or((0.0, 0.0));
    let y_bounds = bounds(paths.iter().flat_map(|p| p.1.iter())).unwrap_or((0.0, 0.0));

    let chart_builder = || {
        let mut builder = ChartBuilder::on(&chart_area);
        builder
            .margin(10)
            .x_label_area_size(45)
            .y_label_area_size(75);
        builder
    };
    // Building a chart draws nothing: a probe gives the plotting area's size.
    let pixels = chart_builder()
        .build_cartesian_2d(0.0..1.0, 0.0..1.0)
        .map_err(failed)?
        .plotting_area()
        .dim_in_pixel();
    let (x_axis, y_axis) = equal_scale(x_bounds, y_bounds, pixels);
    let mut chart = chart_builder()
        .build_cartesian_2d(x_axis, y_axis)
        .map_err(failed)?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&tick_label)
        .y_label_formatter(&tick_label)
        .max_light_lines(4)
        .label_style((FAMILY, LABEL_SIZE))
        .axis_desc_style((FAMILY, AXIS_DESC_SIZE))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(205, 205, 205))
        .draw()
        .map_err(failed)?;

    let rows = stride_indices(data.len(), MAX_PATH_POINTS);
    let project = |xs: &[f64], ys: &[f64]| rows.iter().map(|&i| (xs[i], ys[i])).collect::<Vec<_>>();
    let mut legend = Vec::new();

    // Body outlines first, so the paths draw over them.
    let outlines = if labels.outline_instants > 0 {
        outline_rows(
            &data.t,
            labels.settle.unwrap_or(data.t[0]),
            labels.outline_instants,
        )
    } else {
        Vec::new()
    };
    for &row in &outlines {
        let g = (data.g[a][row], data.g[b][row]);
        let mut corners: Vec<(f64, f64)> = data
            .wheels
            .iter()
            .map(|wheel| (wheel.centre[a][row], wheel.centre[b][row]))
            .collect();
        corners.push(g);
        let mut hull = convex_hull(&corners);
        if let Some(&first) = hull.first() {
            hull.push(first);
        }
        chart
            .draw_series(std::iter::once(PathElement::new(
                hull,
                MARKER.stroke_width(1),
            )))
            .map_err(failed)?;
        chart
            .draw_series(std::iter::once(Cross::new(g, 5, MARKER.stroke_width(1))))
            .map_err(failed)?;
    }
    if !outlines.is_empty() {
        legend.push(LegendEntry {
            width: 1,
            ..LegendEntry::solid(
                match outlines.len() {
                    1 => "body at the end".to_string(),
                    k => format!("body at {k} instants"),
                },
                MARKER,
            )
        });
    }

    for (j, (wheel, name)) in data.wheels.iter().zip(&labels.wheel_names).enumerate() {
        let colour = wheel_colour(j);
        chart
            .draw_series(LineSeries::new(
                project(&wheel.contact[a], &wheel.contact[b]),
                tint(colour).stroke_width(1),
            ))
            .map_err(failed)?;
        chart
            .draw_series(LineSeries::new(
                project(&wheel.centre[a], &wheel.centre[b]),
                colour.stroke_width(LINE_WIDTH),
            ))
            .map_err(failed)?;
        legend.push(LegendEntry::solid(format!("{name} wheel centre"), colour));
        legend.push(LegendEntry {
            width: 1,
            ..LegendEntry::solid(format!("{name} contact point"), tint(colour))
        });
    }

    chart
        .draw_series(LineSeries::new(
            project(&data.g[a], &data.g[b]),
            BODY.stroke_width(LINE_WIDTH),
        ))
        .map_err(failed)?;
    legend.insert(0, LegendEntry::solid("G (centre of mass)", BODY));

    let start = (data.g[a][0], data.g[b][0]);
    chart
        .draw_series(std::iter::once(Circle::new(start, 4, BODY.filled())))
        .map_err(failed)?;
    chart
        .draw_series(std::iter::once(
            EmptyElement::at(start) + Text::new("start", (6, 4), (FAMILY, LABEL_SIZE)),
        ))
        .map_err(failed)?;
    if let Some(ts) = labels.settle {
        let row = nearest_row(&data.t, ts);
        let g = (data.g[a][row], data.g[b][row]);
        let text = TextStyle::from((FAMILY, LABEL_SIZE).into_font()).color(&MARKER);
        chart
            .draw_series(std::iter::once(
                EmptyElement::at(g)
                    + Circle::new((0, 0), 5, MARKER.stroke_width(2))
                    + Text::new(
                        format!("settled, t = {} s", tick_label(&ts)),
                        (7, -16),
                        text,
                    ),
            ))
            .map_err(failed)?;
    }

    draw_legend(&legend_area, &legend, 30)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outline_instants_span_settling_to_end() {
        let t: Vec<f64> = (0..=100).map(|i| i as f64 * 0.1).collect();
        assert_eq!(outline_rows(&t, 2.0, 5), vec![20, 40, 60, 80, 100]);
        assert_eq!(outline_rows(&t, 0.0, 1), vec![100]);
        // A single-row run: one outline.
        assert_eq!(outline_rows(&[0.0], 0.0, 4), vec![0]);
    }
}
