//! Hostile input: huge headers, truncated files, non-finite values.

use std::path::Path;

use rover_terrain::*;

use super::files::{PLACE, PNG_SCALE, asc};
use super::support::*;

// ---------------------------------------------------------------- robustness

/// Mutated and truncated files never panic a reader: they load or they error.
#[test]
fn readers_never_panic_on_damaged_files() {
    let grid = bumpy_grid(7, 5);
    let samples: Vec<(&str, Vec<u8>)> = vec![
        ("asc", asc::format_asc(&grid).into_bytes()),
        ("csv", csv_grid::format_csv(&grid).into_bytes()),
        (
            "png",
            png_map::encode_png(
                &Grid::new([0.0, 0.0], [1.0, 1.0], 7, 5, vec![1.0; 35]).unwrap(),
                SampleScale {
                    scale: 0.01,
                    offset: 0.0,
                },
            )
            .unwrap(),
        ),
        ("tif", geotiff::encode_geotiff(&grid).unwrap()),
    ];
    let path = Path::new("damaged");
    let mut r = prng::SplitMix64::new(99);
    let mut outcomes = [0usize; 2];
    for (kind, original) in &samples {
        for round in 0..400 {
            let mut bytes = original.clone();
            match round % 4 {
                0 => bytes.truncate((r.next_u64() % bytes.len() as u64) as usize),
                1 => {
                    for _ in 0..1 + r.next_u64() % 4 {
                        let k = (r.next_u64() % bytes.len() as u64) as usize;
                        bytes[k] = r.next_u64() as u8;
                    }
                }
                2 => {
                    let k = (r.next_u64() % bytes.len() as u64) as usize;
                    let printable = b"0123456789-.eE \n,#naifNAIF";
                    bytes[k] = printable[(r.next_u64() % printable.len() as u64) as usize];
                }
                _ => {
                    let k = (r.next_u64() % bytes.len() as u64) as usize;
                    bytes.insert(k, r.next_u64() as u8);
                }
            }
            let ok = match *kind {
                "asc" => asc::parse_asc(&String::from_utf8_lossy(&bytes), path).is_ok(),
                "csv" => csv_grid::parse_csv(&String::from_utf8_lossy(&bytes), path, None).is_ok(),
                "png" => png_map::decode_png(&bytes, path, PLACE, PNG_SCALE).is_ok(),
                _ => geotiff::decode_geotiff(&bytes, path, 1.0, 0.0).is_ok(),
            };
            outcomes[usize::from(ok)] += 1;
        }
    }
    // Both outcomes happen: the damage is sometimes harmless, often fatal.
    assert!(outcomes[0] > 100 && outcomes[1] > 10, "{outcomes:?}");
}

/// A header claiming a huge grid gets an error, not a huge allocation.
#[test]
fn huge_headers_do_not_allocate_their_claims() {
    let (path, grid) = asc(
        "huge.asc",
        "ncols 100000000\nnrows 100000000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n",
    );
    assert_eq!(
        message(grid),
        format!(
            "{}: the grid is 100000000 × 100000000 = 10000000000000000 nodes; at most 50000000 \
             are loaded\n  = help: crop or downsample the map (gdal_translate -outsize, or \
             -srcwin) to the area the rover drives over",
            path.display()
        )
    );
}
