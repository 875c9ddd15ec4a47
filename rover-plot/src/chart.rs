//! Plain line charts (several series, one panel) for comparisons that are
//! not a single run: R against R_k, a sweep, levels or suspensions side by
//! side (docs/REPRODUCTION.md).

use std::path::{Path, PathBuf};

use plotters::prelude::*;

use crate::PlotError;
use crate::font::{FAMILY, register_embedded_font};
use crate::style::PALETTE;

/// One series of a chart.
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// Legend label.
    pub name: String,
    /// (x, y) points, drawn in order.
    pub points: Vec<(f64, f64)>,
    /// Draw markers at the points instead of a line.
    pub markers: bool,
}

const SIZE: (u32, u32) = (900, 600);

/// Draw `series` into `<stem>.png` and `<stem>.svg`; returns both paths.
pub fn line_chart(
    stem: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series],
) -> Result<Vec<PathBuf>, PlotError> {
    register_embedded_font();
    let name: &'static str = "chart";
    let draw_error = |message: String| PlotError::Draw {
        figure: name,
        message,
    };
    let finite: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect();
    if finite.is_empty() {
        return Err(draw_error(format!("{title}: no finite point to draw")));
    }
    let pad = |lo: f64, hi: f64| {
        let span = (hi - lo).abs().max(1e-9 * (1.0 + hi.abs()));
        (lo - 0.05 * span, hi + 0.05 * span)
    };
    let (x0, x1) = pad(
        finite.iter().map(|p| p.0).fold(f64::INFINITY, f64::min),
        finite.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max),
    );
    let (y0, y1) = pad(
        finite.iter().map(|p| p.1).fold(f64::INFINITY, f64::min),
        finite.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max),
    );
    fn draw<DB: DrawingBackend>(
        root: DrawingArea<DB, plotters::coord::Shift>,
        title: &str,
        labels: (&str, &str),
        ranges: ((f64, f64), (f64, f64)),
        series: &[Series],
    ) -> Result<(), String> {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, (FAMILY, 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(ranges.0.0..ranges.0.1, ranges.1.0..ranges.1.1)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(labels.0)
            .y_desc(labels.1)
            .label_style((FAMILY, 14))
            .draw()
            .map_err(|e| e.to_string())?;
        for (i, s) in series.iter().enumerate() {
            let colour = PALETTE[i % PALETTE.len()];
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|(x, y)| x.is_finite() && y.is_finite())
                .collect();
            let anno = if s.markers {
                chart
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 5, colour.filled())))
                    .map_err(|e| e.to_string())?
            } else {
                chart
                    .draw_series(LineSeries::new(pts, colour.stroke_width(2)))
                    .map_err(|e| e.to_string())?
            };
            anno.label(s.name.clone()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(3))
            });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font((FAMILY, 14))
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())
    }
    let ranges = ((x0, x1), (y0, y1));
    let mut svg = String::new();
    draw(
        SVGBackend::with_string(&mut svg, SIZE).into_drawing_area(),
        title,
        (x_label, y_label),
        ranges,
        series,
    )
    .map_err(draw_error)?;
    let mut rgb = vec![255u8; 3 * (SIZE.0 * SIZE.1) as usize];
    draw(
        BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area(),
        title,
        (x_label, y_label),
        ranges,
        series,
    )
    .map_err(draw_error)?;
    let png_bytes = crate::render::encode_png(&rgb, SIZE).map_err(draw_error)?;
    let svg_path = stem.with_extension("svg");
    let png_path = stem.with_extension("png");
    let write = |p: &Path, bytes: &[u8]| {
        rover_files::write_whole(p, bytes).map_err(|source| PlotError::Write {
            path: p.to_path_buf(),
            source,
        })
    };
    write(&png_path, &png_bytes)?;
    write(&svg_path, svg.as_bytes())?;
    Ok(vec![png_path, svg_path])
}
