//! 16-bit grayscale PNG height maps.
//!
//! Each pixel is one grid node; the image's top row is the north edge (row 1
//! at `Y = y0 + (height−1)·dy`), its left column the west edge. A sample `k`
//! (0 … 65535, stored big-endian as PNG requires) is the height
//! ```text
//! Z = offset + scale·k      \[m\]
//! ```
//! A PNG carries no georeference: the scenario gives `origin` (the centre of
//! the bottom-left pixel) and `spacing`. Only 16-bit grayscale is accepted:
//! an 8-bit map has only 256 levels (a 2.5 m relief in 1 cm terraces), and
//! a colour image has no single height per pixel.

use std::io::Cursor;
use std::path::Path;

use super::error::{FileError, Place, TerrainError};
use super::georeference::Georeference;
use super::grid::Grid;
use super::io::{read_bytes, write_bytes};
use super::param::finite;

/// The vertical mapping of PNG samples: `Z = offset + scale·k`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleScale {
    /// Metres per count (non-zero; negative flips the relief).
    pub scale: f64,
    /// Height \[m\] of sample 0.
    pub offset: f64,
}

impl SampleScale {
    fn check(&self) -> Result<SampleScale, TerrainError> {
        finite("offset", self.offset, "m")?;
        if !(self.scale.is_finite() && self.scale != 0.0) {
            return Err(TerrainError::parameter(
                "scale",
                format!(
                    "must be a finite, non-zero number of metres per count, got {}",
                    self.scale
                ),
                "e.g. scale = 0.001 maps sample 1000 to 1 m above offset",
            ));
        }
        Ok(*self)
    }
}

/// Reads a 16-bit grayscale PNG height map placed by `georeference`.
pub fn read_png(
    path: &Path,
    georeference: Georeference,
    scale: SampleScale,
) -> Result<Grid, TerrainError> {
    decode_png(&read_bytes(path)?, path, georeference, scale)
}

/// Decodes PNG `bytes`; `path` names the file in errors.
pub fn decode_png(
    bytes: &[u8],
    path: &Path,
    georeference: Georeference,
    scale: SampleScale,
) -> Result<Grid, TerrainError> {
    let georeference = georeference.check()?;
    let scale = scale.check()?;
    let samples = decode_samples(bytes, path, Samples::Heights)?;
    let heights = samples
        .values
        .iter()
        .map(|&k| scale.offset + scale.scale * f64::from(k))
        .collect();
    Grid::new(
        georeference.origin,
        georeference.spacing,
        samples.width,
        samples.height,
        heights,
    )
}

/// What a PNG's samples are, which decides the images accepted.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Samples {
    /// Heights: 16-bit grayscale only (8 bits give 256 levels).
    Heights,
    /// Soil classes: 8- or 16-bit grayscale (a class is an integer).
    Classes,
}

impl Samples {
    /// What the image is called in messages.
    fn noun(self) -> &'static str {
        match self {
            Samples::Heights => "height map",
            Samples::Classes => "soil map",
        }
    }
}

/// A grayscale image's samples, south row first, west to east.
pub(crate) struct Image {
    pub width: usize,
    pub height: usize,
    pub values: Vec<u16>,
}

/// Decodes the grayscale samples of PNG `bytes`; `path` names the file in
/// errors.
pub(crate) fn decode_samples(
    bytes: &[u8],
    path: &Path,
    kind: Samples,
) -> Result<Image, TerrainError> {
    let whole = |problem: String, help: &str| FileError::at(path, Place::Whole, problem, help);
    let decoder = png::Decoder::new(Cursor::new(bytes));
    let mut reader = decoder.read_info().map_err(|e| {
        whole(
            format!("not a readable PNG image ({e})"),
            "check that the file is a complete PNG (re-export or re-copy it), or set format",
        )
    })?;
    let info = reader.info();
    let (width, height) = (info.width as usize, info.height as usize);
    let (color, depth) = (info.color_type, info.bit_depth);
    let bytes_per_sample = match (kind, depth) {
        (_, png::BitDepth::Sixteen) => 2,
        (Samples::Classes, png::BitDepth::Eight) => 1,
        _ => 0,
    };
    if color != png::ColorType::Grayscale || bytes_per_sample == 0 {
        return Err(match kind {
            Samples::Heights => whole(
                format!(
                    "the image is {}-bit {color:?}; a height map must be 16-bit Grayscale",
                    depth as u8
                ),
                "re-export the height map as a 16-bit grayscale PNG (8 bits give only 256 \
                 height levels; colour has no single height per pixel)",
            ),
            Samples::Classes => whole(
                format!(
                    "the image is {}-bit {color:?}; a soil map must be 8- or 16-bit Grayscale",
                    depth as u8
                ),
                "re-export the soil map as a grayscale PNG whose pixel values are the classes \
                 (no palette, no colour, no alpha)",
            ),
        });
    }
    if width < 2 || height < 2 {
        return Err(whole(
            format!("the image is {width} × {height} pixels; a grid needs at least 2 × 2"),
            &format!(
                "give a {} of at least two rows and two columns",
                kind.noun()
            ),
        ));
    }
    super::grid::check_file_nodes(path, width, height)?;
    let size = reader.output_buffer_size().ok_or_else(|| {
        whole(
            format!("the image ({width} × {height}) is too large to decode"),
            &format!("crop or downsample the {}", kind.noun()),
        )
    })?;
    let mut buffer = vec![0; size];
    let frame = reader.next_frame(&mut buffer).map_err(|e| {
        whole(
            format!("the image data is corrupt or truncated ({e})"),
            "re-export or re-copy the file",
        )
    })?;
    let line = frame.line_size;
    let mut values = vec![0; width * height];
    for r in 0..height {
        let j = height - 1 - r;
        let row = buffer
            .get(r * line..r * line + bytes_per_sample * width)
            .unwrap_or(&[]);
        for (i, sample) in row.chunks_exact(bytes_per_sample).enumerate() {
            values[j * width + i] = match sample {
                [hi, lo] => u16::from_be_bytes([*hi, *lo]),
                [k] => u16::from(*k),
                _ => 0,
            };
        }
    }
    Ok(Image {
        width,
        height,
        values,
    })
}

/// Writes `grid` as a 16-bit grayscale PNG, each height quantized to
/// `k = round((Z − offset)/scale)`; an error if a height falls outside 0 … 65535.
pub fn write_png(grid: &Grid, path: &Path, scale: SampleScale) -> Result<(), TerrainError> {
    write_bytes(path, &encode_png(grid, scale)?)
}

/// The PNG bytes of `grid` (see [`write_png`]).
pub fn encode_png(grid: &Grid, scale: SampleScale) -> Result<Vec<u8>, TerrainError> {
    let scale = scale.check()?;
    let (nx, ny) = (grid.nx(), grid.ny());
    let too_big = || {
        TerrainError::parameter(
            "grid",
            format!("{nx} × {ny} nodes do not fit a PNG image"),
            "split the grid",
        )
    };
    let width = u32::try_from(nx).map_err(|_| too_big())?;
    let height = u32::try_from(ny).map_err(|_| too_big())?;
    let mut data = Vec::with_capacity(2 * nx * ny);
    for j in (0..ny).rev() {
        for i in 0..nx {
            let z = grid.node(i, j).unwrap_or(0.0);
            let k = ((z - scale.offset) / scale.scale).round();
            if !(0.0..=65535.0).contains(&k) {
                return Err(TerrainError::parameter(
                    "scale",
                    format!(
                        "the height {z} m at node (i = {i}, j = {j}) maps to sample {k}, \
                         outside 0 … 65535"
                    ),
                    "choose offset below the lowest height and scale so that the highest fits",
                ));
            }
            data.extend_from_slice(&(k as u16).to_be_bytes());
        }
    }
    let encode_error = |e: png::EncodingError| {
        TerrainError::parameter(
            "grid",
            format!("the PNG encoder failed: {e}"),
            "write the grid in another format (asc, csv, geotiff)",
        )
    };
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::Sixteen);
    let mut writer = encoder.write_header().map_err(encode_error)?;
    writer.write_image_data(&data).map_err(encode_error)?;
    writer.finish().map_err(encode_error)?;
    Ok(out)
}
