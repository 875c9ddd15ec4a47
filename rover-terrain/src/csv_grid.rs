//! CSV grids: a plain matrix of heights, with an optional georeference header.
//!
//! ```text
//! # comment lines start with '#' and may appear anywhere; blank lines are ignored
//! x0,y0,dx,dy              optional header: these four keys, any order and case
//! 0.0,0.0,0.5,0.5          ... and their values on the next line \[m\]
//! 1.0,1.1,1.2,1.3          row 1: Y = y0 (the south row), X = x0, x0 + dx, ... (west to east)
//! 0.9,1.0,1.1,1.2          row 2: Y = y0 + dy
//! 0.8,0.9,1.0,1.1          ...
//! ```
//! Unlike ESRI grids and images, **rows run south to north**: row k of the
//! matrix is `Y = y0 + (k−1)·dy`, column i is `X = x0 + (i−1)·dx` — the layout
//! of `numpy.savetxt(Z, delimiter=",")` or MATLAB's `writematrix(Z)` for
//! `Z[j, i] = Z_G(x_i, y_j)` on a `meshgrid`. Every row has as many values as
//! the first. Without the header, the scenario gives `origin = [x0, y0]` and
//! `spacing = [dx, dy]`; giving both is an error, so the two cannot disagree
//! silently. The writer always writes the header.

use std::fmt::Write as _;
use std::path::Path;

use super::error::{FileError, Place, TerrainError};
use super::georeference::Georeference;
use super::grid::Grid;
use super::io::{read_text, write_bytes};

/// Reads a CSV grid; `georeference` places a matrix that has no header.
pub fn read_csv(path: &Path, georeference: Option<Georeference>) -> Result<Grid, TerrainError> {
    parse_csv(&read_text(path)?, path, georeference)
}

/// Writes `grid` as a CSV grid with its header.
pub fn write_csv(grid: &Grid, path: &Path) -> Result<(), TerrainError> {
    write_bytes(path, format_csv(grid).as_bytes())
}

/// The CSV text of `grid`.
pub fn format_csv(grid: &Grid) -> String {
    let [x0, y0] = grid.origin();
    let [dx, dy] = grid.spacing();
    let mut out = String::from(
        "# rover terrain grid: heights [m]; row k is Y = y0 + (k-1)*dy (south first), \
         column i is X = x0 + (i-1)*dx\n",
    );
    // Writing to a String cannot fail.
    let _ = writeln!(out, "x0,y0,dx,dy\n{x0},{y0},{dx},{dy}");
    for row in grid.heights().chunks(grid.nx()) {
        for (i, z) in row.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            rover_files::push_f64(&mut out, *z);
        }
        out.push('\n');
    }
    out
}

const KEYS: [&str; 4] = ["x0", "y0", "dx", "dy"];

/// Parses CSV grid `text`; `path` names the file in errors.
pub fn parse_csv(
    text: &str,
    path: &Path,
    georeference: Option<Georeference>,
) -> Result<Grid, TerrainError> {
    let m = parse_matrix(text, path, georeference, &HEIGHTS)?;
    Grid::new(
        m.georeference.origin,
        m.georeference.spacing,
        m.nx,
        m.ny,
        m.values,
    )
}

/// What a CSV matrix's cells hold, for its error messages: heights, or
/// the soil classes of a soil map.
pub(crate) struct Cells {
    /// One cell's value: "height".
    pub noun: &'static str,
    /// What the values are written as: "heights are decimal numbers in metres".
    pub form: &'static str,
    /// The unit a finite value is given in: " in metres".
    pub unit: &'static str,
    /// The scenario table that gives origin and spacing.
    pub table: &'static str,
}

/// A terrain grid's cells.
const HEIGHTS: Cells = Cells {
    noun: "height",
    form: "heights are decimal numbers in metres",
    unit: " in metres",
    table: "[terrain]",
};

/// A CSV matrix as read: placed, its values south row first, and the line
/// of the file each row came from (for the errors of a caller that checks
/// the values further).
pub(crate) struct Matrix {
    pub georeference: Georeference,
    pub nx: usize,
    pub ny: usize,
    pub values: Vec<f64>,
    pub lines: Vec<usize>,
}

/// Parses the CSV matrix `text` of `cells`; `path` names the file in errors.
pub(crate) fn parse_matrix(
    text: &str,
    path: &Path,
    georeference: Option<Georeference>,
    cells: &Cells,
) -> Result<Matrix, TerrainError> {
    let err = |line: usize, problem: String, help: &str| {
        FileError::at(path, Place::Line(line), problem, help)
    };
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(k, l)| (k + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'))
        .peekable();

    // The optional header: a line of keys, then a line of values.
    let mut from_file: Option<Georeference> = None;
    if let Some(&(number, line)) = lines.peek() {
        let first = line.split(',').next().unwrap_or("").trim();
        if first.parse::<f64>().is_err() {
            lines.next();
            let keys: Vec<String> = line
                .split(',')
                .map(|k| k.trim().to_ascii_lowercase())
                .collect();
            let mut order = [usize::MAX; 4];
            for (position, key) in keys.iter().enumerate() {
                let Some(k) = KEYS.iter().position(|name| name == key) else {
                    return Err(err(
                        number,
                        format!("unknown header key `{key}`"),
                        "the header line is `x0,y0,dx,dy` (any order); heights follow as numbers",
                    ));
                };
                if order[k] != usize::MAX {
                    return Err(err(
                        number,
                        format!("header key `{key}` is given twice"),
                        "the header line is `x0,y0,dx,dy`, each key once",
                    ));
                }
                order[k] = position;
            }
            if let Some(k) = order.iter().position(|&p| p == usize::MAX) {
                return Err(err(
                    number,
                    format!("the header has no `{}`", KEYS[k]),
                    "the header line is `x0,y0,dx,dy`, each key once",
                ));
            }
            let Some((value_line, values)) = lines.next() else {
                return Err(err(
                    number,
                    "the header line is not followed by its values".into(),
                    "after `x0,y0,dx,dy` put a line with the four numbers in metres",
                ));
            };
            let values: Vec<&str> = values.split(',').map(str::trim).collect();
            if values.len() != 4 {
                return Err(err(
                    value_line,
                    format!(
                        "the header has 4 keys but this line has {} values",
                        values.len()
                    ),
                    "give x0, y0, dx and dy, in the order of the header line",
                ));
            }
            let mut numbers = [0.0; 4];
            for (k, slot) in numbers.iter_mut().enumerate() {
                let word = values.get(order[k]).copied().unwrap_or("");
                *slot = match word.parse::<f64>() {
                    Ok(v) if v.is_finite() => v,
                    _ => {
                        return Err(err(
                            value_line,
                            format!(
                                "the value of `{}` is `{word}`, not a finite number",
                                KEYS[k]
                            ),
                            "give x0, y0, dx and dy as numbers in metres",
                        ));
                    }
                };
            }
            for k in [2, 3] {
                if numbers[k] <= 0.0 {
                    return Err(err(
                        value_line,
                        format!("`{}` must be > 0, got {}", KEYS[k], numbers[k]),
                        "dx and dy are the distances between neighbouring nodes in metres",
                    ));
                }
            }
            from_file = Some(Georeference {
                origin: [numbers[0], numbers[1]],
                spacing: [numbers[2], numbers[3]],
            });
        }
    }
    let first_data = lines.peek().map_or(1, |&(n, _)| n);
    let georeference = match (from_file, georeference) {
        (Some(g), None) => g,
        (None, Some(g)) => g.check()?,
        (Some(_), Some(_)) => {
            return Err(err(
                first_data,
                "the file has an `x0,y0,dx,dy` header and the scenario gives origin and \
                 spacing too"
                    .into(),
                &format!(
                    "remove origin and spacing from {} or the header from the file, so the \
                     two cannot disagree",
                    cells.table
                ),
            ));
        }
        (None, None) => {
            return Err(err(
                first_data,
                "the grid has no georeference: no `x0,y0,dx,dy` header".into(),
                &format!(
                    "add the header line `x0,y0,dx,dy` and a line with their values before the \
                     {}s, or set origin = [x0, y0] and spacing = [dx, dy] in {}",
                    cells.noun, cells.table
                ),
            ));
        }
    };

    let mut heights = Vec::new();
    let mut row_lines = Vec::new();
    let mut ncols = 0;
    let mut nrows = 0;
    for (number, line) in lines {
        nrows += 1;
        row_lines.push(number);
        let mut count = 0;
        for (c, word) in line.split(',').map(str::trim).enumerate() {
            let c = c + 1;
            count += 1;
            if word.is_empty() {
                return Err(err(
                    number,
                    format!("row {nrows}, column {c} is empty"),
                    &format!(
                        "every cell needs a {}; check for a doubled or trailing comma",
                        cells.noun
                    ),
                ));
            }
            let Ok(z) = word.parse::<f64>() else {
                return Err(err(
                    number,
                    format!(
                        "row {nrows}, column {c}: `{}` is not a number",
                        rover_files::excerpt(word, 24)
                    ),
                    &format!("{}, separated by commas", cells.form),
                ));
            };
            if !z.is_finite() {
                return Err(err(
                    number,
                    format!(
                        "row {nrows}, column {c}: the {} {word} is not a finite number",
                        cells.noun
                    ),
                    &format!(
                        "every cell needs a finite {}{}; fill holes before loading",
                        cells.noun, cells.unit
                    ),
                ));
            }
            heights.push(z);
        }
        if nrows == 1 {
            ncols = count;
        } else if count != ncols {
            return Err(err(
                number,
                format!("row {nrows} has {count} values, expected {ncols} as in the first row"),
                "every row of the matrix has one value per column; check for a missing or \
                 extra value (or a truncated file)",
            ));
        }
    }
    if nrows < 2 || ncols < 2 {
        return Err(err(
            first_data,
            format!("the matrix has {nrows} rows of {ncols} values; a grid needs at least 2 × 2"),
            &format!("give at least two rows of at least two {}s", cells.noun),
        ));
    }
    Ok(Matrix {
        georeference,
        nx: ncols,
        ny: nrows,
        values: heights,
        lines: row_lines,
    })
}
