//! Logs held in memory as columns of numbers, by name, as the Python
//! module passes them (a sensor log, a run's truth): the error that
//! locates a value in them, and the check that every column has one value
//! per instant.

/// Columns of numbers that do not fit what they should hold: the table
/// (`sensors`, `truth`), the column and the element, what is wrong and how
/// to fix it. Rendered as the table is indexed in Python,
/// `sensors["gx"][12]: …`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{table}{}{}: {problem}\n  = help: {help}", column.as_ref().map(|c| format!("[\"{c}\"]")).unwrap_or_default(), index.map(|i| format!("[{i}]")).unwrap_or_default())]
pub struct ColumnsError {
    /// The table's name.
    pub table: &'static str,
    /// The column, when the error is in one.
    pub column: Option<String>,
    /// The element (0-based), when the error is at one.
    pub index: Option<usize>,
    /// What is wrong.
    pub problem: String,
    /// How to fix it.
    pub help: String,
}

/// The length of column `t` of `table`, once every column in `used` (by
/// position in `columns`) is checked to have as many values: one value
/// per instant. `columns[used[0]]` is `t`.
pub(crate) fn common_length(
    table: &'static str,
    columns: &[(&str, &[f64])],
    used: impl IntoIterator<Item = usize>,
    help: &str,
) -> Result<usize, ColumnsError> {
    let mut used = used.into_iter();
    let Some(t) = used.next() else {
        return Ok(0);
    };
    let rows = columns[t].1.len();
    for k in used {
        let (name, values) = columns[k];
        if values.len() != rows {
            return Err(ColumnsError {
                table,
                column: Some(name.to_string()),
                index: None,
                problem: format!(
                    "{} values, where `{}` has {rows}",
                    values.len(),
                    columns[t].0
                ),
                help: help.to_string(),
            });
        }
    }
    Ok(rows)
}
