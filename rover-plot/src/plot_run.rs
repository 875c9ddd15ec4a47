//! The entry point: read a run CSV, draw every figure, write PNG and SVG.

use std::path::{Path, PathBuf};

use crate::figure::Figure;
use crate::labels::Labels;
use crate::render::{render_png, render_svg};
use crate::run_data::RunData;
use crate::{PlotError, PlotMeta};

/// Plots the run in `csv` into `out_dir` (created if missing): for each
/// [`Figure`] in [`Figure::ALL`] order, `<stem>.png` then `<stem>.svg`.
/// Returns the paths written.
///
/// Every figure is drawn in memory before the first file is written, so bad
/// input leaves no partial set of plots. The same CSV and `meta` give
/// byte-identical files.
///
/// # Errors
/// A [`PlotError`] naming the file and the line or column when the CSV is
/// missing, malformed, lacks a column, holds a non-numeric or non-finite
/// value, or has no data row; when `meta` does not fit the CSV; or when a
/// file cannot be written.
pub fn plot_run(csv: &Path, out_dir: &Path, meta: &PlotMeta) -> Result<Vec<PathBuf>, PlotError> {
    crate::font::register_embedded_font();
    let data = RunData::from_csv(csv)?;
    let labels = Labels::resolve(csv, meta, &data)?;

    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::with_capacity(2 * Figure::ALL.len());
    for figure in Figure::ALL {
        let png = render_png(figure, &data, &labels)?;
        let svg = render_svg(figure, &data, &labels)?;
        files.push((out_dir.join(format!("{}.png", figure.stem())), png));
        files.push((
            out_dir.join(format!("{}.svg", figure.stem())),
            svg.into_bytes(),
        ));
    }

    rover_files::OutputDir::create(out_dir).map_err(|source| PlotError::Write {
        path: out_dir.to_path_buf(),
        source,
    })?;
    let mut written = Vec::with_capacity(files.len());
    for (path, bytes) in files {
        rover_files::write_whole(&path, &bytes).map_err(|source| PlotError::Write {
            path: path.clone(),
            source,
        })?;
        written.push(path);
    }
    Ok(written)
}
