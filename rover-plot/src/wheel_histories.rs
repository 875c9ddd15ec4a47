//! Per-wheel time histories on one panel: the motor torques (`torques`) and
//! the normal forces (`forces`), one coloured line per wheel.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::axis_range::time_axis;
use crate::draw_result::{DrawResult, failed};
use crate::font::FAMILY;
use crate::labels::Labels;
use crate::run_data::RunData;
use crate::style::{TITLE_SIZE, wheel_colour};
use crate::time_panel::{Line, TimePanel, draw_time_panel};

/// Which per-wheel quantity to plot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum WheelQuantity {
    /// `tau{j}`, N·m.
    Torque,
    /// `Fn{j}`, N.
    NormalForce,
}

/// Draws one line per wheel of `quantity` against time.
pub(crate) fn draw_wheel_quantity<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    data: &RunData,
    labels: &Labels,
    quantity: WheelQuantity,
) -> DrawResult {
    root.fill(&WHITE).map_err(failed)?;
    let (what, y_desc) = match quantity {
        WheelQuantity::Torque => ("motor torques", "τ [N·m]"),
        WheelQuantity::NormalForce => ("normal forces", "Fn [N]"),
    };
    let area = root
        .titled(&format!("{} — {what}", labels.title), (FAMILY, TITLE_SIZE))
        .map_err(failed)?;
    let lines = data
        .wheels
        .iter()
        .zip(&labels.wheel_names)
        .enumerate()
        .map(|(j, (wheel, name))| Line {
            label: Some(name.clone()),
            colour: wheel_colour(j),
            dashed: false,
            t: &data.t,
            values: match quantity {
                WheelQuantity::Torque => wheel.torque.clone(),
                WheelQuantity::NormalForce => wheel.normal_force.clone(),
            },
        })
        .collect();
    let panel = TimePanel {
        caption: String::new(),
        y_desc: y_desc.to_string(),
        lines,
    };
    draw_time_panel(&area, &panel, time_axis(&data.t), labels.settle)
}
