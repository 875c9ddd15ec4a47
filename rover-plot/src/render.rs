//! Drawing a figure on both back ends: SVG text and PNG bytes, in memory,
//! before anything is written.

use plotters::prelude::*;

use crate::PlotError;
use crate::figure::Figure;
use crate::labels::Labels;
use crate::run_data::RunData;

/// The SVG document of `figure`.
pub(crate) fn render_svg(
    figure: Figure,
    data: &RunData,
    labels: &Labels,
) -> Result<String, PlotError> {
    let draw_error = |message| PlotError::Draw {
        figure: figure.stem(),
        message,
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, figure.size()).into_drawing_area();
        figure.draw(&root, data, labels).map_err(draw_error)?;
        root.present().map_err(|e| draw_error(e.to_string()))?;
    }
    Ok(svg)
}

/// The PNG file of `figure` (8-bit RGB).
pub(crate) fn render_png(
    figure: Figure,
    data: &RunData,
    labels: &Labels,
) -> Result<Vec<u8>, PlotError> {
    let draw_error = |message| PlotError::Draw {
        figure: figure.stem(),
        message,
    };
    let (w, h) = figure.size();
    let mut rgb = vec![255u8; 3 * w as usize * h as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        figure.draw(&root, data, labels).map_err(draw_error)?;
        root.present().map_err(|e| draw_error(e.to_string()))?;
    }
    encode_png(&rgb, (w, h)).map_err(draw_error)
}

/// An 8-bit RGB buffer as PNG file bytes (the message on failure).
pub(crate) fn encode_png(rgb: &[u8], (w, h): (u32, u32)) -> Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, w, h);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let png_error = |e: png::EncodingError| format!("PNG encoding: {e}");
    let mut writer = encoder.write_header().map_err(png_error)?;
    writer.write_image_data(rgb).map_err(png_error)?;
    writer.finish().map_err(png_error)?;
    Ok(bytes)
}

/// A picture drawn alike on any back end.
pub(crate) trait Drawing {
    /// Draws it on `root`.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> crate::draw_result::DrawResult;
}

/// `drawing` of `size` rendered in memory and written as `<stem>.png` and
/// `<stem>.svg` into `out_dir`: both drawn before either is written.
pub(crate) fn write_drawing(
    drawing: &impl Drawing,
    stem: &'static str,
    size: (u32, u32),
    out_dir: &std::path::Path,
) -> Result<Vec<std::path::PathBuf>, PlotError> {
    let draw_error = |message| PlotError::Draw {
        figure: stem,
        message,
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        drawing.draw(&root).map_err(draw_error)?;
        root.present().map_err(|e| draw_error(e.to_string()))?;
    }
    let mut rgb = vec![255u8; 3 * size.0 as usize * size.1 as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        drawing.draw(&root).map_err(draw_error)?;
        root.present().map_err(|e| draw_error(e.to_string()))?;
    }
    let png = encode_png(&rgb, size).map_err(draw_error)?;
    let mut written = Vec::new();
    for (ext, bytes) in [("png", png), ("svg", svg.into_bytes())] {
        let path = out_dir.join(format!("{stem}.{ext}"));
        rover_files::write_whole(&path, &bytes).map_err(|source| PlotError::Write {
            path: path.clone(),
            source,
        })?;
        written.push(path);
    }
    Ok(written)
}
