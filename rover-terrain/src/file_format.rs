//! The terrain file formats, and loading a grid from a file of any of them.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::asc::read_asc;
use super::csv_grid::read_csv;
use super::error::TerrainError;
use super::georeference::Georeference;
use super::grid::Grid;

/// A terrain file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FileFormat {
    /// ESRI ASCII grid (`.asc`), see the `asc` module.
    Asc,
    /// CSV matrix (`.csv`), see the `csv_grid` module.
    Csv,
    /// 16-bit grayscale PNG height map (`.png`), see the `png_map` module.
    Png,
    /// GeoTIFF DEM (`.tif`, `.tiff`), see the `geotiff` module.
    Geotiff,
}

impl FileFormat {
    /// The format a file name's extension implies (case-insensitive).
    pub fn from_path(path: &Path) -> Result<FileFormat, TerrainError> {
        let extension = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match extension.as_deref() {
            Some("asc") => Ok(FileFormat::Asc),
            Some("csv") => Ok(FileFormat::Csv),
            Some("png") => Ok(FileFormat::Png),
            Some("tif" | "tiff") => Ok(FileFormat::Geotiff),
            _ => Err(TerrainError::parameter(
                "format",
                format!(
                    "cannot tell the format of `{}` from its extension",
                    path.display()
                ),
                "set format = \"asc\", \"csv\", \"png\" or \"geotiff\"",
            )),
        }
    }
}

/// What a file needs besides its own content.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadOptions {
    /// Placement for files without one (PNG always, CSV without header).
    pub georeference: Option<Georeference>,
    /// Heights are `offset + scale·value` \[m\]; required for PNG.
    pub scale: Option<f64>,
    /// See `scale` \[m\].
    pub offset: f64,
}

/// Loads a grid from `path` in `format`.
///
/// `scale`/`offset` apply to every format (unit conversions, datum shifts);
/// a georeference given for a format that carries its own (asc, geotiff) is
/// an error, so the two cannot disagree.
pub fn load_grid(
    path: &Path,
    format: FileFormat,
    options: LoadOptions,
) -> Result<Grid, TerrainError> {
    let refuse_georeference = |format: &str| {
        if options.georeference.is_some() {
            Err(TerrainError::parameter(
                "origin",
                format!("{format} files carry their own origin and spacing"),
                "remove origin and spacing from [terrain]",
            ))
        } else {
            Ok(())
        }
    };
    let grid = match format {
        FileFormat::Asc => {
            refuse_georeference("ESRI ASCII grid")?;
            read_asc(path)?
        }
        FileFormat::Csv => read_csv(path, options.georeference)?,
        FileFormat::Geotiff => {
            refuse_georeference("GeoTIFF")?;
            return load_geotiff(path, options);
        }
        FileFormat::Png => return load_png(path, options),
    };
    rescale(grid, options.scale.unwrap_or(1.0), options.offset)
}

/// A PNG height map: it carries no georeference and no height scale, so
/// the scenario gives both.
#[cfg(feature = "png")]
fn load_png(path: &Path, options: LoadOptions) -> Result<Grid, TerrainError> {
    use super::png_map::{SampleScale, read_png};
    let Some(georeference) = options.georeference else {
        return Err(TerrainError::parameter(
            "origin",
            "a PNG height map needs origin and spacing".to_string(),
            "set origin = [x, y] (centre of the bottom-left pixel) and \
             spacing = [dx, dy] in metres",
        ));
    };
    let Some(scale) = options.scale else {
        return Err(TerrainError::parameter(
            "scale",
            "a PNG height map needs scale (metres per count)".to_string(),
            "set scale (and offset, the height of sample 0), e.g. scale = 0.001",
        ));
    };
    let scale = SampleScale {
        scale,
        offset: options.offset,
    };
    read_png(path, georeference, scale)
}

#[cfg(not(feature = "png"))]
fn load_png(_: &Path, _: LoadOptions) -> Result<Grid, TerrainError> {
    Err(missing_feature("PNG height maps", "png"))
}

/// A GeoTIFF DEM, with its own georeference.
#[cfg(feature = "geotiff")]
fn load_geotiff(path: &Path, options: LoadOptions) -> Result<Grid, TerrainError> {
    super::geotiff::read_geotiff(path, options.scale.unwrap_or(1.0), options.offset)
}

#[cfg(not(feature = "geotiff"))]
fn load_geotiff(_: &Path, _: LoadOptions) -> Result<Grid, TerrainError> {
    Err(missing_feature("GeoTIFF DEMs", "geotiff"))
}

/// The error of a format whose reader this build left out.
#[cfg(not(all(feature = "png", feature = "geotiff")))]
fn missing_feature(what: &str, feature: &str) -> TerrainError {
    TerrainError::parameter(
        "format",
        format!("this build of rover-terrain reads no {what}"),
        format!(
            "enable the `{feature}` feature of rover-terrain, or convert the file to .asc or .csv"
        ),
    )
}

/// Applies `offset + scale·z` to a text grid's heights.
fn rescale(grid: Grid, scale: f64, offset: f64) -> Result<Grid, TerrainError> {
    if scale == 1.0 && offset == 0.0 {
        return Ok(grid);
    }
    super::param::finite("scale", scale, "m per unit")?;
    super::param::finite("offset", offset, "m")?;
    let heights = grid.heights().iter().map(|z| offset + scale * z).collect();
    Grid::new(grid.origin(), grid.spacing(), grid.nx(), grid.ny(), heights)
}
