//! GeoTIFF digital elevation models (single band, north-up).
//!
//! Read with the `tiff` crate: any single-band sample type (8/16/32/64-bit
//! integers, 32/64-bit floats, any compression the crate knows). The
//! georeference comes from the tags
//! ```text
//! ModelPixelScale (33550)  [sx, sy, sz]         pixel size \[m\]; sx, sy > 0
//! ModelTiepoint   (33922)  [I, J, K, X, Y, Z]   raster point (I, J) is at model (X, Y)
//! GeoKeyDirectory (34735)  key 1025 GTRasterTypeGeoKey: 1 PixelIsArea (default), 2 PixelIsPoint
//! GDAL_NODATA     (42113)  optional ASCII number marking cells without data
//! ```
//! Pixel (column c, row r), row 0 at the top (north), becomes the node at
//! `X = X_t + (c − I + h)·sx`, `Y = Y_t − (r − J + h)·sy`, with `h = 1/2` for
//! PixelIsArea (the tie point is a pixel corner) and `h = 0` for PixelIsPoint.
//! Rotated or sheared rasters (ModelTransformation) are refused, and so are
//! cells equal to GDAL_NODATA (an error naming the pixel: fill or crop first).
//! A height is `offset + scale·value` (by default the value in metres).
//!
//! The writer stores 64-bit floats with PixelIsPoint and the tie point on the
//! south-west node, so write → read gives the same grid bit for bit.

use std::io::Cursor;
use std::path::Path;

use tiff::decoder::{Decoder, DecodingResult};
use tiff::encoder::{TiffEncoder, colortype::Gray64Float};
use tiff::tags::Tag;
use tiff::{ColorType, TiffError};

use super::error::{FileError, Place, TerrainError};
use super::grid::Grid;
use super::io::{read_bytes, write_bytes};
use super::param::finite;

const PIXEL_SCALE: (&str, u16) = ("ModelPixelScale", 33550);
const TIEPOINT: (&str, u16) = ("ModelTiepoint", 33922);
const GEO_KEYS: (&str, u16) = ("GeoKeyDirectory", 34735);
const NODATA: (&str, u16) = ("GDAL_NODATA", 42113);
const TRANSFORMATION: (&str, u16) = ("ModelTransformation", 34264);
/// GTRasterTypeGeoKey and its PixelIsPoint value.
const RASTER_TYPE_KEY: u16 = 1025;
const PIXEL_IS_POINT: u16 = 2;

/// Reads a GeoTIFF DEM; heights are `offset + scale·value` \[m\].
pub fn read_geotiff(path: &Path, scale: f64, offset: f64) -> Result<Grid, TerrainError> {
    decode_geotiff(&read_bytes(path)?, path, scale, offset)
}

/// Decodes GeoTIFF `bytes`; `path` names the file in errors.
pub fn decode_geotiff(
    bytes: &[u8],
    path: &Path,
    scale: f64,
    offset: f64,
) -> Result<Grid, TerrainError> {
    finite("scale", scale, "m per unit")?;
    finite("offset", offset, "m")?;
    let whole = |problem: String, help: &str| FileError::at(path, Place::Whole, problem, help);
    let tag_error = |(name, number): (&'static str, u16), problem: String, help: &str| {
        FileError::at(path, Place::Tag(name, number), problem, help)
    };
    let corrupt = |e: TiffError| {
        whole(
            format!("not a readable TIFF image ({e})"),
            "check that the file is a complete GeoTIFF (re-export or re-copy it)",
        )
    };
    let mut decoder = Decoder::new(Cursor::new(bytes)).map_err(corrupt)?;
    let (width, height) = decoder.dimensions().map_err(corrupt)?;
    let (width, height) = (width as usize, height as usize);
    match decoder.colortype().map_err(corrupt)? {
        ColorType::Gray(_) => {}
        other => {
            return Err(whole(
                format!("the image is {other:?}; a DEM has one band of heights"),
                "export the elevation band alone (e.g. gdal_translate -b 1)",
            ));
        }
    }
    if width < 2 || height < 2 {
        return Err(whole(
            format!("the image is {width} × {height} pixels; a grid needs at least 2 × 2"),
            "give a DEM of at least two rows and two columns",
        ));
    }
    super::grid::check_file_nodes(path, width, height)?;

    // Georeference.
    let doubles =
        |decoder: &mut Decoder<Cursor<&[u8]>>, tag: Tag, which: (&'static str, u16)| match decoder
            .find_tag(tag)
        {
            Ok(Some(value)) => value.into_f64_vec().map(Some).map_err(|e| {
                tag_error(
                    which,
                    format!("cannot be read as numbers ({e})"),
                    "re-export the DEM with GDAL (gdal_translate -of GTiff)",
                )
            }),
            Ok(None) => Ok(None),
            Err(e) => Err(corrupt(e)),
        };
    let pixel_scale = doubles(&mut decoder, Tag::ModelPixelScaleTag, PIXEL_SCALE)?;
    let tiepoint = doubles(&mut decoder, Tag::ModelTiepointTag, TIEPOINT)?;
    // A transformation matrix places the raster, whatever else is given:
    // it may rotate or shear it, which a grid cannot represent.
    let rotated = matches!(decoder.find_tag(Tag::ModelTransformationTag), Ok(Some(_)));
    if rotated {
        return Err(tag_error(
            TRANSFORMATION,
            "the raster is placed by a transformation matrix, which may rotate or shear it".into(),
            "warp the DEM north-up first (gdalwarp), which writes ModelPixelScale and \
             ModelTiepoint alone",
        ));
    }
    let Some(pixel_scale) = pixel_scale else {
        return Err(tag_error(
            PIXEL_SCALE,
            "is missing: the TIFF has no georeference".into(),
            "export a GeoTIFF (gdal_translate -of GTiff, with a spatial reference), or \
             convert the DEM to .asc",
        ));
    };
    let [sx, sy] = match pixel_scale.as_slice() {
        [sx, sy, ..] if sx.is_finite() && *sx > 0.0 && sy.is_finite() && *sy > 0.0 => [*sx, *sy],
        other => {
            return Err(tag_error(
                PIXEL_SCALE,
                format!("must start with two pixel sizes > 0, got {other:?}"),
                "re-export the DEM north-up with square positive pixels (gdalwarp)",
            ));
        }
    };
    let Some(tiepoint) = tiepoint else {
        return Err(tag_error(
            TIEPOINT,
            "is missing: the TIFF has a pixel size but no position".into(),
            "re-export the DEM as a GeoTIFF (gdal_translate -of GTiff)",
        ));
    };
    let [ti, tj, _, tx, ty, _] = match tiepoint.get(..6) {
        Some(&[i, j, k, x, y, z]) if [i, j, x, y].iter().all(|v| v.is_finite()) => {
            [i, j, k, x, y, z]
        }
        _ => {
            return Err(tag_error(
                TIEPOINT,
                format!("must hold six finite numbers [I, J, K, X, Y, Z], got {tiepoint:?}"),
                "re-export the DEM as a GeoTIFF (gdal_translate -of GTiff)",
            ));
        }
    };
    let half = match decoder.find_tag(Tag::GeoKeyDirectoryTag) {
        Ok(Some(value)) => {
            let keys = value.into_u16_vec().map_err(|e| {
                tag_error(
                    GEO_KEYS,
                    format!("cannot be read as 16-bit numbers ({e})"),
                    "re-export the DEM with GDAL (gdal_translate -of GTiff)",
                )
            })?;
            // Header of 4 shorts, then [key, location, count, value] per key.
            let raster_type = keys
                .get(4..)
                .unwrap_or(&[])
                .chunks_exact(4)
                .find(|k| k[0] == RASTER_TYPE_KEY && k[1] == 0)
                .map(|k| k[3]);
            if raster_type == Some(PIXEL_IS_POINT) {
                0.0
            } else {
                0.5
            }
        }
        Ok(None) => 0.5,
        Err(e) => return Err(corrupt(e)),
    };
    let nodata = match decoder.find_tag(Tag::GdalNodata) {
        Ok(Some(value)) => {
            let text = value.into_string().unwrap_or_default();
            let text = text.trim_matches(|c: char| c == '\0' || c.is_whitespace());
            match text.parse::<f64>() {
                Ok(v) => Some(v),
                Err(_) => {
                    return Err(tag_error(
                        NODATA,
                        format!("`{text}` is not a number"),
                        "GDAL_NODATA holds the no-data value as text, e.g. \"-9999\"; fix it \
                         with gdal_edit.py -a_nodata",
                    ));
                }
            }
        }
        Ok(None) => None,
        Err(e) => return Err(corrupt(e)),
    };

    let image = decoder.read_image().map_err(|e| {
        whole(
            format!("the image data is corrupt or truncated ({e})"),
            "re-export or re-copy the file",
        )
    })?;
    let values: Vec<f64> = match image {
        DecodingResult::U8(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::U64(v) => v.into_iter().map(|x| x as f64).collect(),
        DecodingResult::I8(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::I64(v) => v.into_iter().map(|x| x as f64).collect(),
        DecodingResult::F16(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F32(v) => v.into_iter().map(f64::from).collect(),
        DecodingResult::F64(v) => v,
    };
    if values.len() != width * height {
        return Err(whole(
            format!(
                "the image holds {} samples for {width} × {height} pixels",
                values.len()
            ),
            "export the elevation band alone (e.g. gdal_translate -b 1)",
        ));
    }
    let mut heights = vec![0.0; width * height];
    for (k, &v) in values.iter().enumerate() {
        let (r, c) = (k / width, k % width);
        let pixel = Place::Pixel {
            row: r + 1,
            column: c + 1,
        };
        let is_nodata = nodata.is_some_and(|n| v == n || (n.is_nan() && v.is_nan()));
        if is_nodata {
            return Err(FileError::at(
                path,
                pixel,
                format!("holds the GDAL_NODATA value {v}: the DEM has no height there"),
                "fill the holes before loading (gdal_fillnodata.py) or crop the DEM to the \
                 measured area (gdal_translate -projwin)",
            ));
        }
        let z = offset + scale * v;
        if !z.is_finite() {
            return Err(FileError::at(
                path,
                pixel,
                format!("the height {v} is not a finite number"),
                "every pixel needs a finite height; mark holes with GDAL_NODATA and fill them",
            ));
        }
        heights[(height - 1 - r) * width + c] = z;
    }
    let x0 = tx + (0.0 - ti + half) * sx;
    let y0 = ty - ((height - 1) as f64 - tj + half) * sy;
    Grid::new([x0, y0], [sx, sy], width, height, heights)
}

/// Writes `grid` as a GeoTIFF DEM of 64-bit float heights.
pub fn write_geotiff(grid: &Grid, path: &Path) -> Result<(), TerrainError> {
    let bytes = encode_geotiff(grid).map_err(|e| TerrainError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::other(e),
    })?;
    write_bytes(path, &bytes)
}

/// The GeoTIFF bytes of `grid` (see [`write_geotiff`]).
pub fn encode_geotiff(grid: &Grid) -> Result<Vec<u8>, TiffError> {
    let (nx, ny) = (grid.nx(), grid.ny());
    let [x0, y0] = grid.origin();
    let [dx, dy] = grid.spacing();
    let mut data = Vec::with_capacity(nx * ny);
    for j in (0..ny).rev() {
        data.extend_from_slice(grid.heights().get(j * nx..(j + 1) * nx).unwrap_or(&[]));
    }
    let width = u32::try_from(nx).map_err(|_| TiffError::LimitsExceeded)?;
    let height = u32::try_from(ny).map_err(|_| TiffError::LimitsExceeded)?;
    let mut out = Cursor::new(Vec::new());
    {
        let mut encoder = TiffEncoder::new(&mut out)?;
        let mut image = encoder.new_image::<Gray64Float>(width, height)?;
        let tags = image.encoder();
        tags.write_tag(Tag::ModelPixelScaleTag, &[dx, dy, 0.0][..])?;
        // Tie the south-west node (column 0, bottom row) exactly, pixel-is-point.
        let tie = [0.0, (ny - 1) as f64, 0.0, x0, y0, 0.0];
        tags.write_tag(Tag::ModelTiepointTag, &tie[..])?;
        let keys: [u16; 8] = [1, 1, 0, 1, RASTER_TYPE_KEY, 0, 1, PIXEL_IS_POINT];
        tags.write_tag(Tag::GeoKeyDirectoryTag, &keys[..])?;
        image.write_data(&data)?;
    }
    Ok(out.into_inner())
}
