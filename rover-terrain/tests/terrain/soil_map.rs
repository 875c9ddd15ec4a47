//! Rasters of soil classes read from CSV and PNG files.

use rover_terrain::*;

use crate::files::png_bytes;
use crate::support::*;

const PLACE: Georeference = Georeference {
    origin: [1.0, 2.0],
    spacing: [0.5, 0.25],
};

#[test]
fn a_csv_soil_map_reads_rows_south_first_and_names_where_a_class_first_appears() {
    let path = file(
        "classes.csv",
        "# soil classes\nx0,y0,dx,dy\n1,2,0.5,0.25\n0,0,1\n\n2,0,1\n",
    );
    let f = read_class_raster(&path, None).unwrap();
    assert_eq!((f.raster.nx(), f.raster.ny()), (3, 2));
    assert_eq!(f.raster.nodes(), &[0, 0, 1, 2, 0, 1]);
    assert_eq!(f.raster.georeference(), PLACE);
    assert_eq!(f.raster.classes(), vec![0, 1, 2]);
    assert_eq!(
        f.first_place(2),
        Some(format!("{}:6: row 2, column 1", path.display()))
    );
    assert_eq!(
        f.first_place(1),
        Some(format!("{}:4: row 1, column 3", path.display()))
    );
    assert_eq!(f.first_place(3), None);
    // The map's class at a node is the file's.
    let map = SoilMap::new(None, Some(f.raster.clone()), vec![]).unwrap();
    assert_eq!(map.weights(1.0, 2.25), SoilWeights::single(2));
    assert_eq!(map.weights(2.0, 2.0), SoilWeights::single(1));
}

#[test]
fn a_csv_soil_map_with_a_fraction_a_negative_or_a_large_class_is_refused_naming_the_cell() {
    for (name, text, line, rest) in [
        (
            "fraction.csv",
            "0,1\n# note\n1,1.5\n",
            3,
            "row 2, column 2: the class 1.5 is not a whole number 0 … 65535",
        ),
        (
            "negative.csv",
            "-1,1\n1,1\n",
            1,
            "row 1, column 1: the class -1 is not a whole number 0 … 65535",
        ),
        (
            "large.csv",
            "0,1\n1,65536\n",
            2,
            "row 2, column 2: the class 65536 is not a whole number 0 … 65535",
        ),
    ] {
        let path = file(name, text);
        let e = read_class_raster(&path, Some(PLACE))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with(&format!("{}:{line}: {rest}\n  = help:", path.display())),
            "{e}"
        );
    }
    let path = file("word.csv", "0,sand\n1,1\n");
    let e = read_class_raster(&path, Some(PLACE))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`sand` is not a number") && e.contains("classes are whole numbers 0 … 65535"),
        "{e}"
    );
    let path = file("unplaced.csv", "0,1\n1,1\n");
    let e = read_class_raster(&path, None).unwrap_err().to_string();
    assert!(e.contains("in [terrain.soil_map]"), "{e}");
}

#[test]
fn an_8_or_16_bit_png_soil_map_reads_its_top_row_as_north() {
    let eight = png_bytes(
        3,
        2,
        png::ColorType::Grayscale,
        png::BitDepth::Eight,
        &[4, 5, 6, 1, 2, 3],
    );
    let sixteen = png_bytes(
        3,
        2,
        png::ColorType::Grayscale,
        png::BitDepth::Sixteen,
        &[0, 4, 0, 5, 1, 0, 0, 1, 0, 2, 0, 3],
    );
    for (name, bytes, top_right) in [("eight.png", eight, 6), ("sixteen.png", sixteen, 256)] {
        let path = file(name, bytes);
        let f = read_class_raster(&path, Some(PLACE)).unwrap();
        assert_eq!(f.raster.nodes(), &[1, 2, 3, 4, 5, top_right], "{name}");
        assert_eq!(
            f.first_place(top_right),
            Some(format!("{}: pixel (row 1, column 3)", path.display()))
        );
        assert_eq!(
            f.first_place(1),
            Some(format!("{}: pixel (row 2, column 1)", path.display()))
        );
        let e = read_class_raster(&path, None).unwrap_err().to_string();
        assert!(
            e.starts_with("terrain.soil_map.origin: a PNG soil map needs origin and spacing"),
            "{e}"
        );
    }
    let rgb = file(
        "rgb_classes.png",
        png_bytes(2, 2, png::ColorType::Rgb, png::BitDepth::Eight, &[0; 12]),
    );
    let e = read_class_raster(&rgb, Some(PLACE))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("the image is 8-bit Rgb; a soil map must be 8- or 16-bit Grayscale"),
        "{e}"
    );
    let tif = file("classes.tif", "");
    let e = read_class_raster(&tif, Some(PLACE))
        .unwrap_err()
        .to_string();
    assert!(e.contains("neither a .csv nor a .png file"), "{e}");
}
