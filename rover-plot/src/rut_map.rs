//! The ruts a run left, seen from above (`ruts_map.png` and `.svg`): the
//! rut depth as a colour scale (a colour bar in mm in the legend column)
//! and the path of G over it, with equal scales on both axes.
//!
//! A grid of millions of nodes is drawn as at most [`MAX_BLOCKS`] blocks
//! a side, each the deepest rut of its nodes (a narrow rut is never lost
//! in the thinning); blocks without a rut are not drawn, so the SVG holds
//! one rectangle per block of rut.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::PlotError;
use crate::axis_range::equal_scale;
use crate::decimate::{MAX_PATH_POINTS, stride_indices};
use crate::draw_result::{DrawResult, failed};
use crate::font::FAMILY;
use crate::legend::LEGEND_WIDTH;
use crate::render::{Drawing, write_drawing};
use crate::run_data::RunData;
use crate::style::{AXIS_DESC_SIZE, BODY, LABEL_SIZE, LINE_WIDTH, TITLE_SIZE};
use crate::tick_label::tick_label;

/// Blocks along the longer side of the drawn grid.
pub const MAX_BLOCKS: usize = 400;

/// The figure's size in pixels.
const SIZE: (u32, u32) = (1100, 850);

/// The file stem of the figure.
const STEM: &str = "ruts_map";

/// A rut map to draw: nodes at `origin + (i, j)·spacing`, depths \[m\]
/// (positive down) south row first.
#[derive(Clone, Copy, Debug)]
pub struct RutImage<'a> {
    /// `[X, Y]` of the south-west node \[m\].
    pub origin: [f64; 2],
    /// Node spacing \[m\].
    pub spacing: f64,
    /// `[nx, ny]`.
    pub nodes: [usize; 2],
    /// Rut depth \[m\] at each node, `nx·ny` of them.
    pub depth: &'a [f64],
}

/// Plots the ruts of `map` with the path of G from the run in `csv` into
/// `out_dir` as `ruts_map.png` and `ruts_map.svg`, titled `title`; both
/// are drawn before either is written. Returns the paths written.
///
/// # Errors
/// A [`PlotError`] when the CSV cannot be read (as [`crate::plot_run`]),
/// when `map` holds fewer depths than its nodes, or a file cannot be
/// written.
pub fn plot_ruts(
    csv: &Path,
    out_dir: &Path,
    title: &str,
    map: &RutImage,
) -> Result<Vec<PathBuf>, PlotError> {
    crate::font::register_embedded_font();
    let data = RunData::from_csv(csv)?;
    let draw_error = |message| PlotError::Draw {
        figure: STEM,
        message,
    };
    let [nx, ny] = map.nodes;
    if map.depth.len() != nx.saturating_mul(ny) || nx == 0 || ny == 0 {
        return Err(draw_error(format!(
            "the rut map has {} depths for {nx} × {ny} nodes",
            map.depth.len()
        )));
    }
    let blocks = Blocks::of(map);
    let drawing = RutDrawing {
        data: &data,
        blocks: &blocks,
        title,
    };
    write_drawing(&drawing, STEM, SIZE, out_dir)
}

/// The rut map's figure.
struct RutDrawing<'a> {
    data: &'a RunData,
    blocks: &'a Blocks,
    title: &'a str,
}

impl Drawing for RutDrawing<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        draw(root, self.data, self.blocks, self.title)
    }
}

/// The map thinned to blocks, each the deepest rut of its nodes.
struct Blocks {
    /// `[X, Y]` of the first block's south-west corner \[m\].
    origin: [f64; 2],
    /// A block's side \[m\].
    side: f64,
    /// `[bx, by]`.
    count: [usize; 2],
    /// The deepest rut of each block \[m\], south row first.
    depth: Vec<f64>,
    /// The deepest of all \[m\].
    deepest: f64,
}

impl Blocks {
    fn of(map: &RutImage) -> Blocks {
        let [nx, ny] = map.nodes;
        let per = nx.max(ny).div_ceil(MAX_BLOCKS).max(1);
        let count = [nx.div_ceil(per), ny.div_ceil(per)];
        let mut depth = vec![0.0f64; count[0] * count[1]];
        for j in 0..ny {
            for i in 0..nx {
                let k = (j / per) * count[0] + i / per;
                depth[k] = depth[k].max(map.depth[j * nx + i]);
            }
        }
        let deepest = depth.iter().copied().fold(0.0, f64::max);
        // A node is the centre of its cell: a block's corner lies half a
        // node spacing before its first node.
        let half = 0.5 * map.spacing;
        Blocks {
            origin: [map.origin[0] - half, map.origin[1] - half],
            side: per as f64 * map.spacing,
            count,
            depth,
            deepest,
        }
    }

    fn extent(&self) -> ((f64, f64), (f64, f64)) {
        let [bx, by] = self.count;
        (
            (self.origin[0], self.origin[0] + bx as f64 * self.side),
            (self.origin[1], self.origin[1] + by as f64 * self.side),
        )
    }
}

/// The colour of a rut `s` of the deepest (0 … 1): pale sand to dark
/// brown.
fn colour(s: f64) -> RGBColor {
    let s = s.clamp(0.0, 1.0);
    let lerp = |a: f64, b: f64| (a + s * (b - a)).round() as u8;
    RGBColor(lerp(240.0, 70.0), lerp(220.0, 35.0), lerp(160.0, 15.0))
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    data: &RunData,
    blocks: &Blocks,
    title: &str,
) -> DrawResult {
    root.fill(&WHITE).map_err(failed)?;
    let area = root
        .titled(&format!("{title} — ruts, top view"), (FAMILY, TITLE_SIZE))
        .map_err(failed)?;
    let (w, _) = area.dim_in_pixel();
    let (chart_area, legend_area) = area.split_horizontally(w.saturating_sub(LEGEND_WIDTH));
    let (mut x, mut y) = blocks.extent();
    for (px, py) in data.g[0].iter().zip(&data.g[1]) {
        x = (x.0.min(*px), x.1.max(*px));
        y = (y.0.min(*py), y.1.max(*py));
    }
    let builder = || {
        let mut b = ChartBuilder::on(&chart_area);
        b.margin(10).x_label_area_size(45).y_label_area_size(75);
        b
    };
    let pixels = builder()
        .build_cartesian_2d(0.0..1.0, 0.0..1.0)
        .map_err(failed)?
        .plotting_area()
        .dim_in_pixel();
    let (x_axis, y_axis) = equal_scale(x, y, pixels);
    let mut chart = builder()
        .build_cartesian_2d(x_axis, y_axis)
        .map_err(failed)?;
    chart
        .configure_mesh()
        .x_desc("X [m]")
        .y_desc("Y [m]")
        .x_label_formatter(&tick_label)
        .y_label_formatter(&tick_label)
        .max_light_lines(4)
        .label_style((FAMILY, LABEL_SIZE))
        .axis_desc_style((FAMILY, AXIS_DESC_SIZE))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(205, 205, 205))
        .draw()
        .map_err(failed)?;
    let [bx, _] = blocks.count;
    let deepest = blocks.deepest.max(f64::MIN_POSITIVE);
    let rects = blocks
        .depth
        .iter()
        .enumerate()
        .filter(|(_, d)| **d > 0.0)
        .map(|(k, d)| {
            let (i, j) = ((k % bx) as f64, (k / bx) as f64);
            let x0 = blocks.origin[0] + i * blocks.side;
            let y0 = blocks.origin[1] + j * blocks.side;
            Rectangle::new(
                [(x0, y0), (x0 + blocks.side, y0 + blocks.side)],
                colour(d / deepest).filled(),
            )
        });
    chart.draw_series(rects).map_err(failed)?;
    let rows = stride_indices(data.len(), MAX_PATH_POINTS);
    let path: Vec<(f64, f64)> = rows.iter().map(|&i| (data.g[0][i], data.g[1][i])).collect();
    chart
        .draw_series(LineSeries::new(path, BODY.stroke_width(LINE_WIDTH)))
        .map_err(failed)?;
    if let (Some(&x0), Some(&y0)) = (data.g[0].first(), data.g[1].first()) {
        chart
            .draw_series(std::iter::once(Circle::new((x0, y0), 5, BODY.filled())))
            .map_err(failed)?;
    }
    colour_bar(&legend_area, blocks.deepest)
}

/// The colour bar: the scale from no rut (bottom) to the deepest (top),
/// ticked in mm, and what the path is.
fn colour_bar<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, deepest: f64) -> DrawResult {
    let (left, top, height, width) = (20i32, 60i32, 400i32, 30i32);
    let text = (FAMILY, LABEL_SIZE).into_font().color(&BLACK);
    area.draw(&Text::new("rut depth [mm]", (left, top - 30), text.clone()))
        .map_err(failed)?;
    let steps = 100;
    for k in 0..steps {
        let s = (k as f64 + 0.5) / steps as f64;
        let y1 = top + height - (k * height) / steps;
        let y0 = top + height - ((k + 1) * height) / steps;
        area.draw(&Rectangle::new(
            [(left, y0), (left + width, y1)],
            colour(s).filled(),
        ))
        .map_err(failed)?;
    }
    area.draw(&Rectangle::new(
        [(left, top), (left + width, top + height)],
        BLACK.stroke_width(1),
    ))
    .map_err(failed)?;
    let ticks = 5;
    for k in 0..=ticks {
        let y = top + height - (k * height) / ticks;
        let mm = 1e3 * deepest * k as f64 / ticks as f64;
        area.draw(&PathElement::new(
            vec![(left + width, y), (left + width + 6, y)],
            BLACK.stroke_width(1),
        ))
        .map_err(failed)?;
        area.draw(&Text::new(
            format!("{mm:.2}"),
            (left + width + 10, y - 6),
            text.clone(),
        ))
        .map_err(failed)?;
    }
    let y = top + height + 40;
    area.draw(&PathElement::new(
        vec![(left, y), (left + width, y)],
        BODY.stroke_width(LINE_WIDTH),
    ))
    .map_err(failed)?;
    area.draw(&Text::new("G", (left + width + 10, y - 6), text))
        .map_err(failed)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Thinning keeps each block's deepest rut, so the deepest of the
    /// blocks is the grid's, and a block lies over its own nodes.
    #[test]
    fn blocks_keep_the_deepest_rut() {
        let (nx, ny) = (1001, 37);
        let mut depth = vec![0.0; nx * ny];
        depth[20 * nx + 777] = 0.031;
        depth[3 * nx + 5] = 0.002;
        let map = RutImage {
            origin: [1.0, -2.0],
            spacing: 0.02,
            nodes: [nx, ny],
            depth: &depth,
        };
        let b = Blocks::of(&map);
        assert!(b.count[0] <= MAX_BLOCKS && b.count[1] <= MAX_BLOCKS);
        assert_eq!(b.deepest, 0.031);
        let per = (b.side / 0.02).round() as usize;
        let k = (20 / per) * b.count[0] + 777 / per;
        assert_eq!(b.depth[k], 0.031);
        // The node lies inside its block.
        let (x, y) = (1.0 + 777.0 * 0.02, -2.0 + 20.0 * 0.02);
        let (i, j) = ((777 / per) as f64, (20 / per) as f64);
        assert!(x > b.origin[0] + i * b.side && x < b.origin[0] + (i + 1.0) * b.side);
        assert!(y > b.origin[1] + j * b.side && y < b.origin[1] + (j + 1.0) * b.side);
        assert_eq!(b.depth.iter().filter(|d| **d > 0.0).count(), 2);
    }
}
