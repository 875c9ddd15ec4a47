//! The truth of a simulated run, read back from its `run.csv`, for
//! measuring an estimate against it: each row's time, the state `[x; w]`
//! (docs/MODEL.md §2) and, on a soil, each wheel's slip.

use std::path::{Path, PathBuf};

use crate::columns::{ColumnsError, common_length};

/// A run's truth, one entry per row of its CSV.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TruthLog {
    /// Times \[s\], increasing.
    pub t: Vec<f64>,
    /// The states `[x; w]`, 2N each.
    pub y: Vec<Vec<f64>>,
    /// Each wheel's normal force \[N\] per row.
    pub normal: Vec<Vec<f64>>,
    /// Each wheel's longitudinal slip per row (a run on a soil), else
    /// `None`.
    pub slip: Option<Vec<Vec<f64>>>,
}

/// A truth file that cannot be read: the file, where, what and how to fix it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{}: {problem}\n  = help: {help}", file.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
pub struct TruthError {
    /// The file.
    pub file: PathBuf,
    /// The line (1-based), when the error is on one.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: String,
    /// How to fix it.
    pub help: String,
}

const HELP: &str = "give the run.csv that `rover simulate` wrote with the sensor log (or leave --truth out: no errors are then measured)";

/// The names of the state's columns in a run's CSV, in `[x; w]`'s order,
/// for `m` suspension coordinates.
pub fn state_columns(m: usize) -> Vec<String> {
    let mut names: Vec<String> = ["X", "Y", "Z", "phi", "theta", "psi"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    names.extend((1..=m).map(|i| format!("y{i}")));
    names.extend(
        ["vx", "vy", "vz", "Ox", "Oy", "Oz"]
            .iter()
            .map(|s| s.to_string()),
    );
    names.extend((1..=m).map(|i| format!("dy{i}")));
    names
}

/// Where a run's truth lies among its columns, found by name (in any
/// order): the time, the state `[x; w]`, the wheels' normal forces and,
/// on a soil, their slips. [`read_truth`] and [`truth_from_columns`] both
/// read through it.
struct TruthColumns {
    t: usize,
    state: Vec<usize>,
    normal: Vec<usize>,
    slip: Option<Vec<usize>>,
}

/// Why a row of the truth cannot be taken.
enum RowFault {
    /// The value of this column is not a finite number.
    NotFinite(usize),
    /// The time `t` does not follow the row before.
    NotAfter(f64),
}

impl TruthColumns {
    /// The columns of a rover of `m` suspension coordinates and `wheels`
    /// wheels among `names`; else the problem naming the first one
    /// missing.
    fn find(names: &[&str], m: usize, wheels: usize) -> Result<Self, String> {
        let find = |name: &str| {
            names
                .iter()
                .position(|h| *h == name)
                .ok_or_else(|| format!("no column `{name}`: this is not a run of this rover"))
        };
        let t = find("t")?;
        let state = state_columns(m)
            .iter()
            .map(|c| find(c))
            .collect::<Result<_, _>>()?;
        let normal = (1..=wheels)
            .map(|j| find(&format!("Fn{j}")))
            .collect::<Result<_, _>>()?;
        let slip = (1..=wheels)
            .map(|j| names.iter().position(|h| *h == format!("slip{j}")))
            .collect();
        Ok(Self {
            t,
            state,
            normal,
            slip,
        })
    }

    /// An empty log of these columns.
    fn log(&self) -> TruthLog {
        TruthLog {
            slip: self.slip.as_ref().map(|_| Vec::new()),
            ..TruthLog::default()
        }
    }

    /// Every column read.
    fn used(&self) -> impl Iterator<Item = usize> + '_ {
        std::iter::once(self.t)
            .chain(self.state.iter().copied())
            .chain(self.normal.iter().copied())
            .chain(self.slip.iter().flatten().copied())
    }

    /// Append to `log` the row whose value in column `c` is `value(c)`:
    /// every value finite, the time after the row before's.
    fn push(&self, log: &mut TruthLog, value: impl Fn(usize) -> f64) -> Result<(), RowFault> {
        let number = |c: usize| {
            let v = value(c);
            if v.is_finite() {
                Ok(v)
            } else {
                Err(RowFault::NotFinite(c))
            }
        };
        let t = number(self.t)?;
        if log.t.last().is_some_and(|&last| t <= last) {
            return Err(RowFault::NotAfter(t));
        }
        let many = |cols: &[usize]| cols.iter().map(|&c| number(c)).collect();
        let state = many(&self.state)?;
        let normal = many(&self.normal)?;
        let slip = self.slip.as_deref().map(many).transpose()?;
        log.t.push(t);
        log.y.push(state);
        log.normal.push(normal);
        if let (Some(v), Some(rows)) = (slip, &mut log.slip) {
            rows.push(v);
        }
        Ok(())
    }
}

/// Reads the truth of a rover of `m` suspension coordinates and `wheels`
/// wheels from the run CSV at `path`.
pub fn read_truth(path: &Path, m: usize, wheels: usize) -> Result<TruthLog, TruthError> {
    let text = rover_files::read_text(path, rover_files::Limit::Data).map_err(|e| TruthError {
        file: path.to_path_buf(),
        line: None,
        problem: format!("cannot read it: {e}"),
        help: HELP.into(),
    })?;
    parse_truth(&text, path, m, wheels)
}

/// The truth in a run CSV's `text`, named `path` in messages (see
/// [`read_truth`]).
pub fn parse_truth(
    text: &str,
    path: &Path,
    m: usize,
    wheels: usize,
) -> Result<TruthLog, TruthError> {
    let fail = |line: Option<usize>, problem: String| TruthError {
        file: path.to_path_buf(),
        line,
        problem,
        help: HELP.into(),
    };
    let mut lines = text.lines().enumerate();
    let header: Vec<&str> = lines
        .next()
        .map(|(_, h)| h.split(',').collect())
        .ok_or_else(|| fail(Some(1), "the file is empty".into()))?;
    let columns = TruthColumns::find(&header, m, wheels).map_err(|p| fail(Some(1), p))?;
    let mut log = columns.log();
    for (k, line) in lines {
        if line.is_empty() {
            continue;
        }
        let cells: Vec<&str> = line.split(',').collect();
        let cell = |c: usize| cells.get(c).copied().unwrap_or("");
        let value = |c: usize| cell(c).parse::<f64>().unwrap_or(f64::NAN);
        columns.push(&mut log, value).map_err(|f| {
            fail(
                Some(k + 1),
                match f {
                    RowFault::NotFinite(c) => format!(
                        "column {} (`{}`) holds `{}`, not a finite number",
                        c + 1,
                        header[c],
                        cell(c)
                    ),
                    RowFault::NotAfter(t) => format!("t = {t} does not follow the row before"),
                },
            )
        })?;
    }
    if log.t.is_empty() {
        return Err(fail(None, "the file has a header and no rows".into()));
    }
    Ok(log)
}

/// The truth of a rover of `m` suspension coordinates and `wheels`
/// wheels from a run's columns held in memory (each column's name, as in
/// the run's CSV, and its values, one per row), checked as [`read_truth`]
/// checks a file: the state's, the normal forces' and the time's columns
/// present, every value read finite, the times increasing; and every
/// column read as long as `t`. An error names the column and the element
/// (`truth["phi"][12]`).
pub fn truth_from_columns(
    columns: &[(&str, &[f64])],
    m: usize,
    wheels: usize,
) -> Result<TruthLog, ColumnsError> {
    const HELP_COLUMNS: &str = "give the columns of the run that wrote the sensor log, named as in its run.csv (or no truth: no errors are then measured)";
    let error = |column: Option<&str>, index: Option<usize>, problem: String| ColumnsError {
        table: "truth",
        column: column.map(str::to_string),
        index,
        problem,
        help: HELP_COLUMNS.into(),
    };
    let names: Vec<&str> = columns.iter().map(|(name, _)| *name).collect();
    let found = TruthColumns::find(&names, m, wheels).map_err(|p| error(None, None, p))?;
    let rows = common_length("truth", columns, found.used(), HELP_COLUMNS)?;
    let mut log = found.log();
    for i in 0..rows {
        found
            .push(&mut log, |c| columns[c].1[i])
            .map_err(|f| match f {
                RowFault::NotFinite(c) => error(
                    Some(names[c]),
                    Some(i),
                    format!("the value is {}, not a finite number", columns[c].1[i]),
                ),
                RowFault::NotAfter(t) => error(
                    Some(names[found.t]),
                    Some(i),
                    format!("t = {t} does not follow the time before"),
                ),
            })?;
    }
    if log.t.is_empty() {
        return Err(error(None, None, "the columns hold no value".into()));
    }
    Ok(log)
}
