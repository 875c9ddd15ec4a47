//! The coordinates plot: one small panel per generalized coordinate — X, Y, Z
//! of G (m), roll φ, pitch θ, yaw ψ (degrees), then each suspension
//! coordinate (degrees if angular, else m) — as in the paper's Figs. 9, 14, 15.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::axis_range::time_axis;
use crate::draw_result::{DrawResult, failed};
use crate::font::FAMILY;
use crate::labels::Labels;
use crate::run_data::RunData;
use crate::style::{PALETTE, TITLE_SIZE};
use crate::time_panel::{Line, TimePanel, draw_time_panel};

/// Columns of the panel grid for `panels` panels: 3 up to 12 panels, then 4.
pub(crate) fn grid_columns(panels: usize) -> usize {
    if panels <= 12 { 3 } else { 4 }
}

/// Draws the grid of coordinate panels.
pub(crate) fn draw_coordinates<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    data: &RunData,
    labels: &Labels,
) -> DrawResult {
    root.fill(&WHITE).map_err(failed)?;
    let area = root
        .titled(
            &format!("{} — generalized coordinates", labels.title),
            (FAMILY, TITLE_SIZE),
        )
        .map_err(failed)?;

    let degrees = |v: &[f64]| v.iter().map(|a| a.to_degrees()).collect::<Vec<_>>();
    let mut panels: Vec<(String, String, Vec<f64>)> = vec![
        ("X of G".into(), "X [m]".into(), data.g[0].clone()),
        ("Y of G".into(), "Y [m]".into(), data.g[1].clone()),
        ("Z of G".into(), "Z [m]".into(), data.g[2].clone()),
        ("roll".into(), "φ [deg]".into(), degrees(&data.attitude[0])),
        ("pitch".into(), "θ [deg]".into(), degrees(&data.attitude[1])),
        ("yaw".into(), "ψ [deg]".into(), degrees(&data.attitude[2])),
    ];
    for ((values, name), &angular) in data
        .y
        .iter()
        .zip(&labels.coordinate_names)
        .zip(&labels.angular)
    {
        let (unit, values) = if angular {
            ("deg", degrees(values))
        } else {
            ("m", values.clone())
        };
        panels.push((name.clone(), format!("{name} [{unit}]"), values));
    }

    let columns = grid_columns(panels.len());
    let rows = panels.len().div_ceil(columns);
    let cells = area.split_evenly((rows, columns));
    let t_axis = time_axis(&data.t);
    for (cell, (caption, y_desc, values)) in cells.iter().zip(panels) {
        let panel = TimePanel {
            caption,
            y_desc,
            lines: vec![Line {
                label: None,
                colour: PALETTE[0],
                dashed: false,
                t: &data.t,
                values,
            }],
        };
        draw_time_panel(cell, &panel, t_axis.clone(), labels.settle)?;
    }
    Ok(())
}
