//! Terrain files: ESRI ASCII, CSV, PNG height maps and GeoTIFF DEMs, each read, written and refused when corrupt.

use std::path::PathBuf;

use rover_terrain::*;

use super::support::*;

// ---------------------------------------------------------------- ESRI ASCII grids

/// Parses `text` as an .asc file written to a scratch file; returns the path too.
pub(crate) fn asc(name: &str, text: &str) -> (PathBuf, Result<Grid, TerrainError>) {
    let path = file(name, text);
    let grid = read_asc(&path);
    (path, grid)
}

/// Pins the whole message of a corrupt .asc file: `{path}:{line}: {rest}`.
fn bad_asc(name: &str, text: &str, line: usize, rest: &str) {
    let (path, grid) = asc(name, text);
    assert_eq!(
        message(grid),
        format!("{}:{line}: {rest}", path.display()),
        "case {name}"
    );
}

#[test]
fn asc_round_trips() {
    for (name, grid) in [
        (
            "round_square.asc",
            bumpy_grid(5, 4).with_interpolation(Interpolation::Bicubic),
        ),
        ("round_rect.asc", bumpy_grid(3, 7)),
        (
            "round_square_cells.asc",
            Grid::from_fn([-0.1, 1e3], [0.05, 0.05], 4, 3, |x, y| {
                1e-3 * x * y + 1.0 / 3.0
            })
            .unwrap(),
        ),
    ] {
        let path = scratch(name);
        write_asc(&grid, &path).unwrap();
        assert_eq!(read_asc(&path).unwrap(), grid, "{name}");
    }
}

#[test]
fn asc_reads_corners_any_key_case_and_rows_north_to_south() {
    let text = "NCOLS 3\r\nnRows\t2\r\nXLLCORNER 10\r\nyllcorner -4\r\nCellSize 0.5\r\n\
                NODATA_value -9999\r\n\r\n1 2 3\r\n4\t5 6\r\n";
    let (_, grid) = asc("corner.asc", text);
    let grid = grid.unwrap();
    assert_eq!(
        (grid.origin(), grid.spacing(), grid.nx(), grid.ny()),
        ([10.25, -3.75], [0.5, 0.5], 3, 2)
    );
    // The first row of the file is the north row (j = 1).
    assert_eq!(grid.heights(), &[4.0, 5.0, 6.0, 1.0, 2.0, 3.0]);
    assert_eq!(h(&grid, 10.25, -3.25), 1.0);
    // dx/dy instead of cellsize, centres instead of corners.
    let text = "ncols 2\nnrows 2\nxllcenter 1\nyllcenter 2\ndx 0.5\ndy 0.25\n1 2\n3 4\n";
    let grid = asc("dxdy.asc", text).1.unwrap();
    assert_eq!((grid.origin(), grid.spacing()), ([1.0, 2.0], [0.5, 0.25]));
}

const ASC_HEAD: &str = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n";

#[test]
fn asc_corrupt_files_each_say_what_and_where() {
    let grid_help = "each line holds one whole row of the grid; check for a missing or extra value";
    bad_asc(
        "short_row.asc",
        &format!("{ASC_HEAD}1 2 3\n4 5\n"),
        7,
        &format!("row 2 has 2 values, expected ncols = 3\n  = help: {grid_help}"),
    );
    bad_asc(
        "long_row.asc",
        &format!("{ASC_HEAD}1 2 3 4\n4 5 6\n"),
        6,
        &format!("row 1 has 4 values, expected ncols = 3\n  = help: {grid_help}"),
    );
    bad_asc(
        "word.asc",
        &format!("{ASC_HEAD}1 2 3\n4 five 6\n"),
        7,
        "row 2, column 2: `five` is not a number\n  = help: heights are decimal numbers in metres",
    );
    bad_asc(
        "nan.asc",
        &format!("{ASC_HEAD}1 NaN 3\n4 5 6\n"),
        6,
        "row 1, column 2: the height NaN is not a finite number\n  = help: every cell needs a \
         finite height in metres (mark holes with NODATA_value)",
    );
    bad_asc(
        "nodata.asc",
        &format!("{ASC_HEAD}NODATA_value -9999\n1 2 3\n4 5 -9999\n"),
        8,
        "row 2, column 3 (X = 2.5 m, Y = 0.5 m) holds the NODATA_value -9999: the map has no \
         height there\n  = help: fill the holes before loading (e.g. gdal_fillnodata.py) or \
         crop the map to the measured area",
    );
    bad_asc(
        "missing_nrows.asc",
        "ncols 3\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n",
        5,
        "missing header key `nrows` before the first row of heights\n  = help: the header \
         needs ncols, nrows, xllcorner (or xllcenter), yllcorner (or yllcenter) and cellsize",
    );
    bad_asc(
        "missing_cellsize.asc",
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\n1 2 3\n4 5 6\n",
        5,
        "missing header key `cellsize` before the first row of heights\n  = help: give the \
         cell size in metres (`cellsize 0.05`), or `dx` and `dy` for rectangular cells",
    );
    bad_asc(
        "missing_yll.asc",
        "ncols 3\nnrows 2\nxllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n",
        5,
        "missing header key `yllcorner` before the first row of heights\n  = help: give the \
         south-west cell's corner (xllcorner, yllcorner) or centre (xllcenter, yllcenter) in \
         metres",
    );
    bad_asc(
        "negative_cellsize.asc",
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -0.5\n1 2 3\n4 5 6\n",
        5,
        "`cellsize` must be > 0, got -0.5\n  = help: the cell size is the distance between cell \
         centres in metres",
    );
    bad_asc(
        "zero_dy.asc",
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ndx 1\ndy 0\n1 2 3\n4 5 6\n",
        6,
        "`dy` must be > 0, got 0\n  = help: the cell size is the distance between cell centres \
         in metres",
    );
    bad_asc(
        "truncated.asc",
        "ncols 3\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n",
        7,
        "the file ends after 2 rows of heights, expected nrows = 4\n  = help: the file is \
         truncated, or nrows is wrong",
    );
    bad_asc(
        "header_only.asc",
        ASC_HEAD,
        5,
        "the file ends after 0 rows of heights, expected nrows = 2\n  = help: the file is \
         truncated, or nrows is wrong",
    );
    bad_asc(
        "extra_row.asc",
        &format!("{ASC_HEAD}1 2 3\n4 5 6\n7 8 9\n"),
        8,
        "more rows of heights than nrows = 2\n  = help: make nrows match the number of rows, or \
         remove the extra lines",
    );
    bad_asc(
        "unknown_key.asc",
        "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncelsize 1\n1 2 3\n4 5 6\n",
        5,
        "unknown header key `celsize`\n  = help: the header keys are ncols, nrows, xllcorner or \
         xllcenter, yllcorner or yllcenter, cellsize (or dx and dy) and NODATA_value",
    );
    bad_asc(
        "twice.asc",
        &format!("{ASC_HEAD}CELLSIZE 2\n1 2 3\n4 5 6\n"),
        6,
        "header key `CELLSIZE` is given twice\n  = help: keep one of the two lines",
    );
    bad_asc(
        "corner_and_center.asc",
        &format!("{ASC_HEAD}xllcenter 0.5\n1 2 3\n4 5 6\n"),
        6,
        "both `xllcorner` and `xllcenter` are given\n  = help: keep one: llcorner is the \
         south-west cell's outer corner, llcenter its centre",
    );
    bad_asc(
        "no_value.asc",
        "ncols\nnrows 2\n",
        1,
        "the header line of `ncols` must be a key and one value\n  = help: write one `key value` pair \
         per header line, e.g. `cellsize 0.05`",
    );
    bad_asc(
        "bad_count.asc",
        "ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n",
        1,
        "`ncols` must be a whole number ≥ 2, got 2.5\n  = help: a grid needs at least 2 × 2 \
         cells; ncols counts columns, nrows rows",
    );
    bad_asc(
        "inf_header.asc",
        "ncols 2\nnrows 2\nxllcorner inf\n",
        3,
        "the value of `xllcorner` is `inf`, not a finite number\n  = help: header values are \
         numbers, e.g. `cellsize 0.05`",
    );
    // A binary file given as text.
    let path = file("binary.asc", b"ncols 2\n\xff\xfe\x00PNG");
    assert_eq!(
        message(read_asc(&path)),
        format!(
            "{}:2: byte 8 is not valid UTF-8 text\n  = help: this format is plain text; is it a \
             binary file (PNG, TIFF) with the wrong format or extension?",
            path.display()
        )
    );
    // A missing file.
    let path = scratch("does_not_exist.asc");
    assert_eq!(
        message(read_asc(&path)),
        format!(
            "{}: cannot read the terrain file: No such file or directory (os error 2)\n  = help: \
             check the path (a relative path is resolved from the scenario file's directory)",
            path.display()
        )
    );
}

// ---------------------------------------------------------------- CSV grids

fn bad_csv(name: &str, text: &str, georeference: Option<Georeference>, line: usize, rest: &str) {
    let path = file(name, text);
    assert_eq!(
        message(read_csv(&path, georeference)),
        format!("{}:{line}: {rest}", path.display()),
        "case {name}"
    );
}

pub(crate) const PLACE: Georeference = Georeference {
    origin: [1.0, 2.0],
    spacing: [0.5, 0.25],
};

#[test]
fn csv_round_trips_and_reads_rows_south_to_north() {
    let grid = bumpy_grid(4, 6);
    let path = scratch("round.csv");
    write_csv(&grid, &path).unwrap();
    assert_eq!(read_csv(&path, None).unwrap(), grid);

    // Header keys in any order and case; comments and blank lines anywhere.
    let path = file(
        "order.csv",
        "# a test grid\nDY, dx ,y0,X0\n0.25,0.5,2,1\n\n1,2,3\n# north\n4,5,6\n",
    );
    let grid = read_csv(&path, None).unwrap();
    assert_eq!(
        (grid.origin(), grid.spacing(), grid.nx(), grid.ny()),
        ([1.0, 2.0], [0.5, 0.25], 3, 2)
    );
    assert_eq!(grid.heights(), &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    assert_eq!(h(&grid, 1.0, 2.25), 4.0);

    // A bare matrix placed by the scenario.
    let path = file("bare.csv", "1,2,3\n4,5,6\n");
    let grid = read_csv(&path, Some(PLACE)).unwrap();
    assert_eq!((grid.origin(), grid.spacing()), ([1.0, 2.0], [0.5, 0.25]));
}

#[test]
fn csv_corrupt_files_each_say_what_and_where() {
    let header = "x0,y0,dx,dy\n0,0,1,1\n";
    bad_csv(
        "short_row.csv",
        &format!("{header}1,2,3\n4,5\n"),
        None,
        4,
        "row 2 has 2 values, expected 3 as in the first row\n  = help: every row of the matrix \
         has one value per column; check for a missing or extra value (or a truncated file)",
    );
    bad_csv(
        "word.csv",
        &format!("{header}1,2,3\n4,x,6\n"),
        None,
        4,
        "row 2, column 2: `x` is not a number\n  = help: heights are decimal numbers in metres, \
         separated by commas",
    );
    bad_csv(
        "empty.csv",
        &format!("{header}1,,3\n4,5,6\n"),
        None,
        3,
        "row 1, column 2 is empty\n  = help: every cell needs a height; check for a doubled or \
         trailing comma",
    );
    bad_csv(
        "nan.csv",
        &format!("{header}1,2,3\n4,5,nan\n"),
        None,
        4,
        "row 2, column 3: the height nan is not a finite number\n  = help: every cell needs a \
         finite height in metres; fill holes before loading",
    );
    bad_csv(
        "no_place.csv",
        "1,2\n3,4\n",
        None,
        1,
        "the grid has no georeference: no `x0,y0,dx,dy` header\n  = help: add the header line \
         `x0,y0,dx,dy` and a line with their values before the heights, or set origin = [x0, \
         y0] and spacing = [dx, dy] in [terrain]",
    );
    bad_csv(
        "two_places.csv",
        &format!("{header}1,2\n3,4\n"),
        Some(PLACE),
        3,
        "the file has an `x0,y0,dx,dy` header and the scenario gives origin and spacing too\n  \
         = help: remove origin and spacing from [terrain] or the header from the file, so the \
         two cannot disagree",
    );
    bad_csv(
        "missing_key.csv",
        "x0,y0,dx\n0,0,1\n1,2\n3,4\n",
        None,
        1,
        "the header has no `dy`\n  = help: the header line is `x0,y0,dx,dy`, each key once",
    );
    bad_csv(
        "unknown_key.csv",
        "x0,y0,dx,dz\n0,0,1,1\n1,2\n3,4\n",
        None,
        1,
        "unknown header key `dz`\n  = help: the header line is `x0,y0,dx,dy` (any order); \
         heights follow as numbers",
    );
    bad_csv(
        "negative.csv",
        "x0,y0,dx,dy\n0,0,1,-1\n1,2\n3,4\n",
        None,
        2,
        "`dy` must be > 0, got -1\n  = help: dx and dy are the distances between neighbouring \
         nodes in metres",
    );
    bad_csv(
        "header_values.csv",
        "x0,y0,dx,dy\n0,0,1\n1,2\n3,4\n",
        None,
        2,
        "the header has 4 keys but this line has 3 values\n  = help: give x0, y0, dx and dy, in \
         the order of the header line",
    );
    bad_csv(
        "one_row.csv",
        &format!("{header}1,2,3\n"),
        None,
        3,
        "the matrix has 1 rows of 3 values; a grid needs at least 2 × 2\n  = help: give at \
         least two rows of at least two heights",
    );
}

// ---------------------------------------------------------------- PNG height maps

pub(crate) const PNG_SCALE: SampleScale = SampleScale {
    scale: 0.001,
    offset: -10.0,
};

pub(crate) fn png_bytes(
    width: u32,
    height: u32,
    color: png::ColorType,
    depth: png::BitDepth,
    data: &[u8],
) -> Vec<u8> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(color);
    encoder.set_depth(depth);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(data).unwrap();
    writer.finish().unwrap();
    out
}

fn bad_png(name: &str, bytes: &[u8], rest: &str) {
    let path = file(name, bytes);
    assert_eq!(
        message(read_png(&path, PLACE, PNG_SCALE)),
        format!("{}: {rest}", path.display()),
        "case {name}"
    );
}

#[test]
fn png_round_trips_and_reads_the_top_row_as_north() {
    let mut r = prng::SplitMix64::new(5);
    let heights = (0..5 * 4)
        .map(|_| PNG_SCALE.offset + PNG_SCALE.scale * (r.next_u64() >> 48) as f64)
        .collect();
    let grid = Grid::new(PLACE.origin, PLACE.spacing, 5, 4, heights).unwrap();
    let path = scratch("round.png");
    write_png(&grid, &path, PNG_SCALE).unwrap();
    assert_eq!(read_png(&path, PLACE, PNG_SCALE).unwrap(), grid);

    // 2 × 2 samples, big-endian: top row 1, 2; bottom row 256, 65535.
    let data = [0, 1, 0, 2, 1, 0, 255, 255];
    let path = file(
        "tiny.png",
        png_bytes(
            2,
            2,
            png::ColorType::Grayscale,
            png::BitDepth::Sixteen,
            &data,
        ),
    );
    let grid = read_png(
        &path,
        PLACE,
        SampleScale {
            scale: 0.5,
            offset: 1.0,
        },
    )
    .unwrap();
    assert_eq!(grid.heights(), &[129.0, 32768.5, 1.5, 2.0]);

    // Heights that do not fit the 16-bit range are refused on writing.
    assert_eq!(
        message(write_png(
            &grid,
            &scratch("unfit.png"),
            SampleScale {
                scale: 0.001,
                offset: 0.0
            }
        )),
        "terrain.scale: the height 129 m at node (i = 0, j = 0) maps to sample 129000, outside \
         0 … 65535\n  = help: choose offset below the lowest height and scale so that the \
         highest fits"
    );
}

#[test]
fn png_corrupt_files_each_say_what_and_where() {
    let fix = "re-export the height map as a 16-bit grayscale PNG (8 bits give only 256 height \
               levels; colour has no single height per pixel)";
    bad_png(
        "eight_bit.png",
        &png_bytes(
            2,
            2,
            png::ColorType::Grayscale,
            png::BitDepth::Eight,
            &[1, 2, 3, 4],
        ),
        &format!(
            "the image is 8-bit Grayscale; a height map must be 16-bit Grayscale\n  = help: {fix}"
        ),
    );
    bad_png(
        "rgb.png",
        &png_bytes(2, 2, png::ColorType::Rgb, png::BitDepth::Sixteen, &[0; 24]),
        &format!("the image is 16-bit Rgb; a height map must be 16-bit Grayscale\n  = help: {fix}"),
    );
    let good = png_bytes(
        16,
        16,
        png::ColorType::Grayscale,
        png::BitDepth::Sixteen,
        &[7; 512],
    );
    bad_png(
        "truncated.png",
        &good[..good.len() - 30],
        "the image data is corrupt or truncated (unexpected end of file)\n  = \
         help: re-export or re-copy the file",
    );
    bad_png(
        "not_png.png",
        b"ncols 3\nnrows 2\n",
        "not a readable PNG image (Invalid PNG signature.)\n  = help: check that the \
         file is a complete PNG (re-export or re-copy it), or set format",
    );
    bad_png(
        "one_row.png",
        &png_bytes(
            3,
            1,
            png::ColorType::Grayscale,
            png::BitDepth::Sixteen,
            &[0; 6],
        ),
        "the image is 3 × 1 pixels; a grid needs at least 2 × 2\n  = help: give a height map \
         of at least two rows and two columns",
    );
}

// ---------------------------------------------------------------- GeoTIFF DEMs

/// A hand-made GeoTIFF of i16 samples, tie point at the top-left pixel's
/// corner (PixelIsArea: no GeoKeyDirectory), optional GDAL_NODATA.
fn i16_geotiff(width: u32, height: u32, data: &[i16], nodata: Option<&str>) -> Vec<u8> {
    use tiff::encoder::{TiffEncoder, colortype::GrayI16};
    use tiff::tags::Tag;
    let mut out = std::io::Cursor::new(Vec::new());
    {
        let mut encoder = TiffEncoder::new(&mut out).unwrap();
        let mut image = encoder.new_image::<GrayI16>(width, height).unwrap();
        let tags = image.encoder();
        tags.write_tag(Tag::ModelPixelScaleTag, &[2.0, 3.0, 0.0][..])
            .unwrap();
        tags.write_tag(
            Tag::ModelTiepointTag,
            &[0.0, 0.0, 0.0, 100.0, 500.0, 0.0][..],
        )
        .unwrap();
        if let Some(nodata) = nodata {
            tags.write_tag(Tag::GdalNodata, nodata).unwrap();
        }
        image.write_data(data).unwrap();
    }
    out.into_inner()
}

fn bad_tiff(name: &str, bytes: &[u8], rest: &str) {
    let path = file(name, bytes);
    assert_eq!(
        message(read_geotiff(&path, 1.0, 0.0)),
        format!("{}: {rest}", path.display()),
        "case {name}"
    );
}

#[test]
fn geotiff_round_trips_and_places_pixel_is_area_rasters() {
    let grid = bumpy_grid(6, 3);
    let path = scratch("round.tif");
    write_geotiff(&grid, &path).unwrap();
    assert_eq!(read_geotiff(&path, 1.0, 0.0).unwrap(), grid);

    // PixelIsArea: top-left corner at (100, 500), pixels 2 m × 3 m.
    let path = file(
        "area.tif",
        i16_geotiff(3, 2, &[1, 2, 3, -4, -5, -6], Some("-32768")),
    );
    let grid = read_geotiff(&path, 0.5, 10.0).unwrap();
    assert_eq!(
        (grid.origin(), grid.spacing()),
        ([101.0, 495.5], [2.0, 3.0])
    );
    assert_eq!(grid.heights(), &[8.0, 7.5, 7.0, 10.5, 11.0, 11.5]);
}

#[test]
fn a_geotiff_placed_by_a_transformation_matrix_is_refused_even_with_a_pixel_scale() {
    use tiff::encoder::{TiffEncoder, colortype::GrayI16};
    use tiff::tags::Tag;
    let mut out = std::io::Cursor::new(Vec::new());
    {
        let mut encoder = TiffEncoder::new(&mut out).unwrap();
        let mut image = encoder.new_image::<GrayI16>(2, 2).unwrap();
        let tags = image.encoder();
        tags.write_tag(Tag::ModelPixelScaleTag, &[2.0, 3.0, 0.0][..])
            .unwrap();
        tags.write_tag(
            Tag::ModelTiepointTag,
            &[0.0, 0.0, 0.0, 100.0, 500.0, 0.0][..],
        )
        .unwrap();
        // A 30° rotation.
        let (s, c) = 30f64.to_radians().sin_cos();
        let matrix = [
            2.0 * c,
            -3.0 * s,
            0.0,
            100.0,
            2.0 * s,
            3.0 * c,
            0.0,
            500.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            1.0,
        ];
        tags.write_tag(Tag::ModelTransformationTag, &matrix[..])
            .unwrap();
        image.write_data(&[1i16, 2, 3, 4][..]).unwrap();
    }
    let path = file("rotated.tif", out.into_inner());
    let text = message(read_geotiff(&path, 1.0, 0.0));
    assert!(
        text.contains("tag ModelTransformation (34264)") && text.contains("gdalwarp"),
        "{text}"
    );
}

#[test]
fn geotiff_corrupt_files_each_say_what_and_where() {
    let path = file(
        "hole.tif",
        i16_geotiff(3, 2, &[1, 2, 3, 4, -9999, 6], Some("-9999 ")),
    );
    assert_eq!(
        message(read_geotiff(&path, 1.0, 0.0)),
        format!(
            "{}: pixel (row 2, column 2): holds the GDAL_NODATA value -9999: the DEM has no \
             height there\n  = help: fill the holes before loading (gdal_fillnodata.py) or crop \
             the DEM to the measured area (gdal_translate -projwin)",
            path.display()
        )
    );
    bad_tiff(
        "bad_nodata.tif",
        &i16_geotiff(2, 2, &[1, 2, 3, 4], Some("none")),
        "tag GDAL_NODATA (42113): `none` is not a number\n  = help: GDAL_NODATA holds the \
         no-data value as text, e.g. \"-9999\"; fix it with gdal_edit.py -a_nodata",
    );
    // A plain TIFF: no georeference.
    let mut plain = std::io::Cursor::new(Vec::new());
    tiff::encoder::TiffEncoder::new(&mut plain)
        .unwrap()
        .write_image::<tiff::encoder::colortype::Gray32Float>(2, 2, &[1.0, 2.0, 3.0, 4.0])
        .unwrap();
    bad_tiff(
        "plain.tif",
        plain.get_ref(),
        "tag ModelPixelScale (33550): is missing: the TIFF has no georeference\n  = help: export \
         a GeoTIFF (gdal_translate -of GTiff, with a spatial reference), or convert the DEM to \
         .asc",
    );
    let mut rgb = std::io::Cursor::new(Vec::new());
    tiff::encoder::TiffEncoder::new(&mut rgb)
        .unwrap()
        .write_image::<tiff::encoder::colortype::RGB8>(2, 2, &[0; 12])
        .unwrap();
    bad_tiff(
        "rgb.tif",
        rgb.get_ref(),
        "the image is RGB(8); a DEM has one band of heights\n  = help: export the elevation \
         band alone (e.g. gdal_translate -b 1)",
    );
    let good = i16_geotiff(64, 64, &[3; 64 * 64], None);
    bad_tiff(
        "truncated.tif",
        &good[..4000],
        // The writer puts the directory after the data, so a cut loses the directory.
        "not a readable TIFF image (failed to fill whole buffer)\n  = help: check that the file \
         is a complete GeoTIFF (re-export or re-copy it)",
    );
    bad_tiff(
        "not_tiff.tif",
        b"P5 2 2 255\n....",
        "not a readable TIFF image (format error: TIFF signature not found)\n  = help: check \
         that the file is a complete GeoTIFF (re-export or re-copy it)",
    );
}
