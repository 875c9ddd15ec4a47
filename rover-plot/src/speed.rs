//! The speed plot: the body's forward speed `vx` against the set-point `V_set`.

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::axis_range::time_axis;
use crate::draw_result::{DrawResult, failed};
use crate::font::FAMILY;
use crate::labels::Labels;
use crate::run_data::RunData;
use crate::style::{BODY, PALETTE, TITLE_SIZE};
use crate::time_panel::{Line, TimePanel, draw_time_panel};

/// Draws `vx` (solid) and `V_set` (dashed) against time.
pub(crate) fn draw_speed<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    data: &RunData,
    labels: &Labels,
) -> DrawResult {
    root.fill(&WHITE).map_err(failed)?;
    let area = root
        .titled(
            &format!("{} — forward speed", labels.title),
            (FAMILY, TITLE_SIZE),
        )
        .map_err(failed)?;
    let panel = TimePanel {
        caption: String::new(),
        y_desc: "speed [m/s]".to_string(),
        lines: vec![
            Line {
                label: Some("vx (body)".to_string()),
                colour: PALETTE[0],
                dashed: false,
                t: &data.t,
                values: data.vx.clone(),
            },
            Line {
                label: Some("V_set (set-point)".to_string()),
                colour: BODY,
                dashed: true,
                t: &data.t,
                values: data.v_set.clone(),
            },
        ],
    };
    draw_time_panel(&area, &panel, time_axis(&data.t), labels.settle)
}
