//! ESRI ASCII grids (`.asc`).
//!
//! ```text
//! ncols         4            header: one `key value` per line, keys in any
//! nrows         3            order and any letter case
//! xllcorner     0.0          or xllcenter: the south-west cell's corner / centre \[m\]
//! yllcorner     0.0          or yllcenter
//! cellsize      0.5          or `dx` and `dy` (GDAL's extension for non-square cells)
//! NODATA_value  -9999        optional
//! 1.0 1.1 1.2 1.3            the northernmost row, west to east
//! 0.9 1.0 1.1 1.2            ...
//! 0.8 0.9 1.0 1.1            the southernmost row
//! ```
//! Rows run north to south, one row of `ncols` values per line (values
//! separated by spaces or tabs; blank lines are ignored). Each cell's height
//! is taken at its centre, which becomes a grid node: with `xllcorner` the
//! first node is at `xllcorner + cellsize/2`. A cell holding `NODATA_value` is
//! an error naming the cell: fill holes before loading (e.g. with
//! `gdal_fillnodata.py`) or crop the map. The writer uses `xllcenter`/`yllcenter`
//! and Rust's shortest round-trip formatting, so write → read gives the same grid.

use std::fmt::Write as _;
use std::path::Path;

use super::error::{FileError, Place, TerrainError};
use super::grid::Grid;
use super::io::{read_text, write_bytes};

/// Reads an ESRI ASCII grid file.
pub fn read_asc(path: &Path) -> Result<Grid, TerrainError> {
    parse_asc(&read_text(path)?, path)
}

/// Writes `grid` as an ESRI ASCII grid file.
pub fn write_asc(grid: &Grid, path: &Path) -> Result<(), TerrainError> {
    write_bytes(path, format_asc(grid).as_bytes())
}

/// The ESRI ASCII grid text of `grid`.
pub fn format_asc(grid: &Grid) -> String {
    let [x0, y0] = grid.origin();
    let [dx, dy] = grid.spacing();
    let mut out = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(out, "ncols {}\nnrows {}", grid.nx(), grid.ny());
    let _ = writeln!(out, "xllcenter {x0}\nyllcenter {y0}");
    if dx == dy {
        let _ = writeln!(out, "cellsize {dx}");
    } else {
        let _ = writeln!(out, "dx {dx}\ndy {dy}");
    }
    for j in (0..grid.ny()).rev() {
        let row = &grid.heights()[j * grid.nx()..(j + 1) * grid.nx()];
        for (i, z) in row.iter().enumerate() {
            if i > 0 {
                out.push(' ');
            }
            rover_files::push_f64(&mut out, *z);
        }
        out.push('\n');
    }
    out
}

/// The header keys, lower-case.
const KEYS: [&str; 10] = [
    "ncols",
    "nrows",
    "xllcorner",
    "xllcenter",
    "yllcorner",
    "yllcenter",
    "cellsize",
    "dx",
    "dy",
    "nodata_value",
];

/// Header values by key index in [`KEYS`], with the line each came from.
#[derive(Default)]
struct Header {
    values: [Option<(f64, usize)>; 10],
}

impl Header {
    fn get(&self, key: &str) -> Option<(f64, usize)> {
        let k = KEYS.iter().position(|&name| name == key)?;
        self.values.get(k).copied().flatten()
    }
}

/// Parses ESRI ASCII grid `text`; `path` names the file in errors.
pub fn parse_asc(text: &str, path: &Path) -> Result<Grid, TerrainError> {
    let err = |line: usize, problem: String, help: &str| {
        FileError::at(path, Place::Line(line), problem, help)
    };
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(k, l)| (k + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty())
        .peekable();

    // Header: lines whose first word is not a number.
    let mut header = Header::default();
    let mut last_line = 0;
    while let Some(&(number, line)) = lines.peek() {
        let mut words = line.split_whitespace();
        let key = words.next().unwrap_or("");
        if key.parse::<f64>().is_ok() {
            break;
        }
        lines.next();
        last_line = number;
        let lower = key.to_ascii_lowercase();
        let Some(k) = KEYS.iter().position(|&name| name == lower) else {
            return Err(err(
                number,
                format!("unknown header key `{key}`"),
                "the header keys are ncols, nrows, xllcorner or xllcenter, yllcorner or \
                 yllcenter, cellsize (or dx and dy) and NODATA_value",
            ));
        };
        let (Some(value), None) = (words.next(), words.next()) else {
            return Err(err(
                number,
                format!("the header line of `{key}` must be a key and one value"),
                "write one `key value` pair per header line, e.g. `cellsize 0.05`",
            ));
        };
        let parsed = match value.parse::<f64>() {
            Ok(v) if v.is_finite() => v,
            _ => {
                return Err(err(
                    number,
                    format!("the value of `{key}` is `{value}`, not a finite number"),
                    "header values are numbers, e.g. `cellsize 0.05`",
                ));
            }
        };
        if header.values[k].is_some() {
            return Err(err(
                number,
                format!("header key `{key}` is given twice"),
                "keep one of the two lines",
            ));
        }
        header.values[k] = Some((parsed, number));
    }
    let data_line = lines.peek().map_or(last_line.max(1), |&(n, _)| n);

    let missing = |key: &str, help: &str| {
        err(
            data_line,
            format!("missing header key `{key}` before the first row of heights"),
            help,
        )
    };
    let count = |key: &str| -> Result<usize, TerrainError> {
        let (value, line) = header.get(key).ok_or_else(|| {
            missing(
                key,
                "the header needs ncols, nrows, xllcorner (or xllcenter), yllcorner (or \
                 yllcenter) and cellsize",
            )
        })?;
        if value.fract() != 0.0 || !(2.0..=1e8).contains(&value) {
            return Err(err(
                line,
                format!("`{key}` must be a whole number ≥ 2, got {value}"),
                "a grid needs at least 2 × 2 cells; ncols counts columns, nrows rows",
            ));
        }
        Ok(value as usize)
    };
    let ncols = count("ncols")?;
    let nrows = count("nrows")?;
    super::grid::check_file_nodes(path, ncols, nrows)?;
    let spacing = |key: &str| -> Result<Option<f64>, TerrainError> {
        match header.get(key) {
            Some((value, line)) if value <= 0.0 => Err(err(
                line,
                format!("`{key}` must be > 0, got {value}"),
                "the cell size is the distance between cell centres in metres",
            )),
            other => Ok(other.map(|(v, _)| v)),
        }
    };
    let (dx, dy) = match (spacing("cellsize")?, spacing("dx")?, spacing("dy")?) {
        (Some(c), None, None) => (c, c),
        (None, Some(dx), Some(dy)) => (dx, dy),
        (None, None, None) => {
            return Err(missing(
                "cellsize",
                "give the cell size in metres (`cellsize 0.05`), or `dx` and `dy` for \
                 rectangular cells",
            ));
        }
        _ => {
            return Err(err(
                data_line,
                "the cell size must be given as `cellsize`, or as both `dx` and `dy`".into(),
                "keep `cellsize` alone for square cells, or `dx` and `dy` together",
            ));
        }
    };
    let corner = |axis: &str, step: f64| -> Result<f64, TerrainError> {
        let corner_key = format!("{axis}llcorner");
        let center_key = format!("{axis}llcenter");
        match (header.get(&corner_key), header.get(&center_key)) {
            (Some((c, _)), None) => Ok(c + 0.5 * step),
            (None, Some((c, _))) => Ok(c),
            (Some(_), Some((_, line))) => Err(err(
                line,
                format!("both `{corner_key}` and `{center_key}` are given"),
                "keep one: llcorner is the south-west cell's outer corner, llcenter its centre",
            )),
            (None, None) => Err(missing(
                &corner_key,
                "give the south-west cell's corner (xllcorner, yllcorner) or centre \
                 (xllcenter, yllcenter) in metres",
            )),
        }
    };
    let x0 = corner("x", dx)?;
    let y0 = corner("y", dy)?;
    let nodata = header.get("nodata_value").map(|(v, _)| v);

    // Rows, north to south: row r (1-based, from the top) is j = nrows − r.
    let mut rows: Vec<Vec<f64>> = Vec::new();
    let mut last = last_line.max(1);
    for (number, line) in lines {
        last = number;
        let r = rows.len() + 1;
        if r > nrows {
            return Err(err(
                number,
                format!("more rows of heights than nrows = {nrows}"),
                "make nrows match the number of rows, or remove the extra lines",
            ));
        }
        // Not sized from the header: a corrupt ncols must not reserve gigabytes.
        let mut row = Vec::new();
        for (c, word) in line.split_whitespace().enumerate() {
            let c = c + 1;
            let Ok(z) = word.parse::<f64>() else {
                return Err(err(
                    number,
                    format!(
                        "row {r}, column {c}: `{}` is not a number",
                        rover_files::excerpt(word, 24)
                    ),
                    "heights are decimal numbers in metres",
                ));
            };
            if Some(z) == nodata {
                let x = x0 + (c - 1) as f64 * dx;
                let y = y0 + (nrows - r) as f64 * dy;
                return Err(err(
                    number,
                    format!(
                        "row {r}, column {c} (X = {x} m, Y = {y} m) holds the NODATA_value {z}: \
                         the map has no height there"
                    ),
                    "fill the holes before loading (e.g. gdal_fillnodata.py) or crop the map \
                     to the measured area",
                ));
            }
            if !z.is_finite() {
                return Err(err(
                    number,
                    format!("row {r}, column {c}: the height {word} is not a finite number"),
                    "every cell needs a finite height in metres (mark holes with NODATA_value)",
                ));
            }
            row.push(z);
        }
        if row.len() != ncols {
            return Err(err(
                number,
                format!("row {r} has {} values, expected ncols = {ncols}", row.len()),
                "each line holds one whole row of the grid; check for a missing or extra value",
            ));
        }
        rows.push(row);
    }
    if rows.len() != nrows {
        return Err(err(
            last,
            format!(
                "the file ends after {} rows of heights, expected nrows = {nrows}",
                rows.len()
            ),
            "the file is truncated, or nrows is wrong",
        ));
    }
    let heights: Vec<f64> = rows.into_iter().rev().flatten().collect();
    Grid::new([x0, y0], [dx, dy], ncols, nrows, heights)
}
