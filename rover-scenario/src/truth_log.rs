//! The truth of a simulated run, read back from its `run.csv`, for
//! measuring an estimate against it: each row's time, the state `[x; w]`
//! (docs/MODEL.md §2) and, on a soil, each wheel's slip.

use std::path::{Path, PathBuf};

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
    let find = |name: &str| {
        header.iter().position(|h| *h == name).ok_or_else(|| {
            fail(
                Some(1),
                format!("no column `{name}`: this is not a run of this rover"),
            )
        })
    };
    let t_col = find("t")?;
    let state: Vec<usize> = state_columns(m)
        .iter()
        .map(|c| find(c))
        .collect::<Result<_, _>>()?;
    let normal: Vec<usize> = (1..=wheels)
        .map(|j| find(&format!("Fn{j}")))
        .collect::<Result<_, _>>()?;
    let slip: Option<Vec<usize>> = (1..=wheels)
        .map(|j| header.iter().position(|h| *h == format!("slip{j}")))
        .collect();
    let mut log = TruthLog {
        slip: slip.as_ref().map(|_| Vec::new()),
        ..TruthLog::default()
    };
    for (k, line) in lines {
        if line.is_empty() {
            continue;
        }
        let cells: Vec<&str> = line.split(',').collect();
        let number = |c: usize| -> Result<f64, TruthError> {
            let cell = cells.get(c).copied().unwrap_or("");
            match cell.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(fail(
                    Some(k + 1),
                    format!(
                        "column {} (`{}`) holds `{cell}`, not a finite number",
                        c + 1,
                        header[c]
                    ),
                )),
            }
        };
        let t = number(t_col)?;
        if log.t.last().is_some_and(|&last| t <= last) {
            return Err(fail(
                Some(k + 1),
                format!("t = {t} does not follow the row before"),
            ));
        }
        log.t.push(t);
        log.y
            .push(state.iter().map(|&c| number(c)).collect::<Result<_, _>>()?);
        log.normal.push(
            normal
                .iter()
                .map(|&c| number(c))
                .collect::<Result<_, _>>()?,
        );
        if let (Some(cols), Some(rows)) = (&slip, &mut log.slip) {
            rows.push(cols.iter().map(|&c| number(c)).collect::<Result<_, _>>()?);
        }
    }
    if log.t.is_empty() {
        return Err(fail(None, "the file has a header and no rows".into()));
    }
    Ok(log)
}
