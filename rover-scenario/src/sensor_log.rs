//! The sensor log, `sensors.csv`: one row per sensor instant of a run
//! with `[sensors]`, its columns those of
//! [`rover_estimate::sensors::columns`] (the names live there only), and
//! its reader, which checks the file against the declaration it was
//! written for.
//!
//! Numbers are written in their shortest form that reads back to the same
//! bits (an exponent below 1e-5 and from 1e16 on); a fix not due that row
//! leaves its cells empty. A non-finite reading is never written.

use std::io::Write;
use std::path::{Path, PathBuf};

use rover_estimate::sensors::{Column, SensorConfig, SensorSample, columns};

use crate::columns::{ColumnsError, common_length};

/// Writes a sensor log: its header, then one row per sample, refusing
/// non-finite readings.
pub struct SensorLogWriter<W: Write> {
    out: W,
    columns: Vec<Column>,
}

impl<W: Write> SensorLogWriter<W> {
    /// Start the log of `config` on a rover of `wheels` wheels and
    /// `coordinates` suspension coordinates with its header.
    pub fn new(
        mut out: W,
        config: &SensorConfig,
        wheels: usize,
        coordinates: usize,
    ) -> std::io::Result<Self> {
        let columns = columns(config, wheels, coordinates);
        let header: Vec<String> = columns.iter().map(Column::to_string).collect();
        writeln!(out, "{}", header.join(","))?;
        Ok(Self { out, columns })
    }

    /// The log's columns.
    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    /// Write the row of `sample`. Allocates nothing.
    pub fn write(&mut self, sample: &SensorSample) -> std::io::Result<()> {
        if let Some((k, c, v)) = self.columns.iter().enumerate().find_map(|(k, c)| {
            c.value(sample)
                .filter(|v| !v.is_finite())
                .map(|v| (k, c, v))
        }) {
            return Err(std::io::Error::other(format!(
                "column {} (`{c}`) is {v} at t = {}: not written",
                k + 1,
                sample.t
            )));
        }
        for (k, c) in self.columns.iter().enumerate() {
            if k > 0 {
                self.out.write_all(b",")?;
            }
            match c.value(sample) {
                Some(v) => write_number(&mut self.out, v)?,
                None if c.sparse() => {}
                None => {
                    return Err(std::io::Error::other(format!(
                        "column {} (`{c}`) has no reading at t = {}: the sample does not fit the log's sensors",
                        k + 1,
                        sample.t
                    )));
                }
            }
        }
        self.out.write_all(b"\n")
    }

    /// Flush and return the sink.
    pub fn into_inner(mut self) -> std::io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}

/// `v` in its shortest exact form: plain from 1e-5 up to 1e16, with an
/// exponent beyond (where the plain form runs to hundreds of digits).
fn write_number(out: &mut impl Write, v: f64) -> std::io::Result<()> {
    let a = v.abs();
    if a == 0.0 || (1e-5..1e16).contains(&a) {
        write!(out, "{v}")
    } else {
        write!(out, "{v:e}")
    }
}

/// A sensor log that does not fit its declaration: the file, where, what
/// is wrong and how to fix it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{}{}: {problem}\n  = help: {help}", file.display(), line.map(|l| format!(":{l}")).unwrap_or_default(), column.as_ref().map(|(k, name)| format!(": column {k} (`{name}`)")).unwrap_or_default())]
pub struct SensorLogError {
    /// The log.
    pub file: PathBuf,
    /// The line (1-based), when the error is on one.
    pub line: Option<usize>,
    /// The column (1-based) and its name, when the error is in one.
    pub column: Option<(usize, String)>,
    /// What is wrong.
    pub problem: String,
    /// How to fix it.
    pub help: String,
}

/// Two times within this fraction of (1 + t) are one instant: the run's
/// sensor instants meet the multiples of the period to rounding.
const SAME_INSTANT: f64 = 1e-9;

/// Read the sensor log at `path` of `config` on a rover of `wheels` wheels
/// and `coordinates` suspension coordinates ([`parse_sensor_log`]).
pub fn read_sensor_log(
    path: &Path,
    config: &SensorConfig,
    wheels: usize,
    coordinates: usize,
) -> Result<Vec<SensorSample>, SensorLogError> {
    let text =
        rover_files::read_text(path, rover_files::Limit::Data).map_err(|e| SensorLogError {
            file: path.to_path_buf(),
            line: rover_files::NotUtf8::of(&e).map(|at| at.line),
            column: None,
            problem: format!("cannot read it: {e}"),
            help: "give the sensors.csv that `rover simulate` wrote for a scenario with [sensors]"
                .into(),
        })?;
    parse_sensor_log(&text, path, config, wheels, coordinates)
}

/// The samples of sensor log `text` (named `file` in messages), checked
/// against `config`: the header names exactly the declaration's columns
/// (in any order), each row has a finite number in every cell but the
/// fixes' (empty when no fix was due, a position fix whole or not at
/// all), and row k is at t = k / rate. The checks are `LogReader`'s,
/// which [`samples_from_columns`] makes too.
pub fn parse_sensor_log(
    text: &str,
    file: &Path,
    config: &SensorConfig,
    wheels: usize,
    coordinates: usize,
) -> Result<Vec<SensorSample>, SensorLogError> {
    let error = |line: Option<usize>, column: Option<(usize, String)>, p: Problem| SensorLogError {
        file: file.to_path_buf(),
        line,
        column,
        problem: p.problem,
        help: p.help,
    };
    let mut reader = LogReader::new(config, wheels, coordinates, Form::File)
        .map_err(|p| error(None, None, p))?;
    let mut lines = text.lines().enumerate();
    let Some((_, header)) = lines.next() else {
        let help = format!("a sensor log starts with the header {}", reader.listing);
        return Err(error(
            None,
            None,
            Problem::new("the file is empty: it has no header", help),
        ));
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    reader.names(&names).map_err(|(k, p)| {
        let at = k.map(|k| (k + 1, names[k].to_string()));
        error(Some(1), at, p)
    })?;
    let order = reader.order.clone();
    let at = |k: usize| Some((k + 1, order[k].to_string()));
    for (i, row) in lines {
        let line = Some(i + 1);
        let cells: Vec<&str> = row.split(',').collect();
        if cells.len() != reader.order.len() {
            return Err(error(
                line,
                None,
                Problem::new(
                    format!(
                        "the row has {} cells, the header {}",
                        cells.len(),
                        reader.order.len()
                    ),
                    "one cell per column in every row (a shorter last row is a log cut off while it was written)",
                ),
            ));
        }
        reader.start_row();
        for (k, cell) in cells.iter().enumerate() {
            let cell = cell.trim();
            let value = if cell.is_empty() {
                None
            } else {
                let c = order[k];
                Some(cell.parse::<f64>().map_err(|_| {
                    error(
                        line,
                        at(k),
                        Problem::new(
                            format!("`{cell}` is not a number"),
                            format!("a decimal number in {}, e.g. 0.25 or -1.5e-3", c.unit()),
                        ),
                    )
                })?)
            };
            reader.cell(k, value).map_err(|p| error(line, at(k), p))?;
        }
        reader.end_row().map_err(|(k, p)| error(line, at(k), p))?;
    }
    Ok(reader.samples)
}

/// The samples of a sensor log held as columns: each column's name (as
/// in `sensors.csv`) and its values, one per sensor instant, NaN in a
/// fix's columns where no fix is due. Checked against `config` as
/// [`parse_sensor_log`] checks a file, by the same `LogReader`: exactly
/// the declaration's columns, a finite reading in every element but the
/// fixes' (a position fix whole or not at all), element k of `t` at
/// k / rate; and every column as long as `t`. An error names the column
/// and the element (`sensors["gx"][12]`).
pub fn samples_from_columns(
    columns: &[(&str, &[f64])],
    config: &SensorConfig,
    wheels: usize,
    coordinates: usize,
) -> Result<Vec<SensorSample>, ColumnsError> {
    let error = |column: Option<&str>, index: Option<usize>, p: Problem| ColumnsError {
        table: "sensors",
        column: column.map(str::to_string),
        index,
        problem: p.problem,
        help: p.help,
    };
    let mut reader = LogReader::new(config, wheels, coordinates, Form::Columns)
        .map_err(|p| error(None, None, p))?;
    let names: Vec<&str> = columns.iter().map(|(name, _)| *name).collect();
    reader
        .names(&names)
        .map_err(|(k, p)| error(k.map(|k| names[k]), None, p))?;
    let t = reader.time_cell();
    let rows = common_length(
        "sensors",
        columns,
        std::iter::once(t).chain((0..columns.len()).filter(|&k| k != t)),
        "one value per sensor instant in every column (NaN in a fix's columns where no fix is due)",
    )?;
    for i in 0..rows {
        reader.start_row();
        for (k, (name, values)) in columns.iter().enumerate() {
            let v = values[i];
            let value = (!(v.is_nan() && reader.order[k].sparse())).then_some(v);
            reader
                .cell(k, value)
                .map_err(|p| error(Some(name), Some(i), p))?;
        }
        reader
            .end_row()
            .map_err(|(k, p)| error(Some(names[k]), Some(i), p))?;
    }
    Ok(reader.samples)
}

/// What is wrong and how to fix it, for the caller to locate.
struct Problem {
    problem: String,
    help: String,
}

impl Problem {
    fn new(problem: impl Into<String>, help: impl Into<String>) -> Self {
        Self {
            problem: problem.into(),
            help: help.into(),
        }
    }
}

/// How a log's rows are carried, for the words of the messages: a file's
/// lines (rows counted from 1 under the header, an empty cell where no
/// fix is due), or columns in memory (elements counted from 0, NaN where
/// no fix is due).
#[derive(Clone, Copy, PartialEq)]
enum Form {
    File,
    Columns,
}

/// The checks of a sensor log against its declaration, whatever carries
/// it: the names ([`LogReader::names`]), then row after row each cell's
/// reading ([`LogReader::cell`]) and the row as a whole
/// ([`LogReader::end_row`]: a position fix whole, the time at its
/// instant). The file reader and the columns' share it; each locates the
/// problems in its own terms.
struct LogReader<'a> {
    config: &'a SensorConfig,
    wheels: usize,
    coordinates: usize,
    form: Form,
    /// The declaration's columns.
    expected: Vec<Column>,
    /// Their names, comma-separated, for messages.
    listing: String,
    /// The column of each cell of a row.
    order: Vec<Column>,
    /// The samples read.
    samples: Vec<SensorSample>,
    /// The row being read and which of its position-fix cells held a
    /// number.
    sample: SensorSample,
    fix_cells: [Option<bool>; 3],
}

impl<'a> LogReader<'a> {
    /// A reader of the log of `config`, once the declaration itself is
    /// checked.
    fn new(
        config: &'a SensorConfig,
        wheels: usize,
        coordinates: usize,
        form: Form,
    ) -> Result<Self, Problem> {
        if let Err(e) = config.check() {
            let (problem, help) = e
                .message
                .split_once("\n  = help: ")
                .unwrap_or((&e.message, ""));
            return Err(Problem::new(
                format!("the declaration to read it with cannot be used: {problem}"),
                help,
            ));
        }
        let expected = columns(config, wheels, coordinates);
        let listing = expected
            .iter()
            .map(Column::to_string)
            .collect::<Vec<_>>()
            .join(",");
        Ok(Self {
            config,
            wheels,
            coordinates,
            form,
            listing,
            order: Vec::with_capacity(expected.len()),
            expected,
            samples: Vec::new(),
            sample: SensorSample::default(),
            fix_cells: [None; 3],
        })
    }

    /// The columns' names in the order of the cells: exactly the
    /// declaration's, each once. An error at a name gives its position.
    fn names(&mut self, names: &[&str]) -> Result<(), (Option<usize>, Problem)> {
        for (k, name) in names.iter().enumerate() {
            let Some(c) = self.expected.iter().find(|c| c.to_string() == *name) else {
                let (problem, help) = undeclared(
                    name,
                    self.config,
                    self.wheels,
                    self.coordinates,
                    &self.listing,
                );
                return Err((Some(k), Problem::new(problem, help)));
            };
            if self.order.contains(c) {
                let help = format!("name each column once: {}", self.listing);
                return Err((Some(k), Problem::new("the column is named twice", help)));
            }
            self.order.push(*c);
        }
        if let Some(missing) = self.expected.iter().find(|c| !self.order.contains(c)) {
            return Err((
                None,
                Problem::new(
                    format!("no column `{missing}`, which {}", declared_by(missing)),
                    format!("the columns of this declaration are {}", self.listing),
                ),
            ));
        }
        Ok(())
    }

    /// The position of the time among the cells.
    fn time_cell(&self) -> usize {
        self.order
            .iter()
            .position(|c| *c == Column::Time)
            .unwrap_or(0)
    }

    /// Begin the next row.
    fn start_row(&mut self) {
        self.sample = SensorSample::sized(self.config, self.wheels, self.coordinates);
        self.fix_cells = [None; 3];
    }

    /// Cell `k` of the row: its reading, `None` for none (a fix not due).
    fn cell(&mut self, k: usize, value: Option<f64>) -> Result<(), Problem> {
        let c = self.order[k];
        let Some(v) = value else {
            if c.sparse() {
                c.set(&mut self.sample, None);
                if let Column::Position(a) = c {
                    self.fix_cells[a] = Some(false);
                }
                return Ok(());
            }
            return Err(Problem::new(
                "the cell is empty",
                format!(
                    "every row reads `{c}` ({}); only the fixes' cells may be empty",
                    c.unit()
                ),
            ));
        };
        if !v.is_finite() {
            let help = match self.form {
                Form::File => {
                    "a reading is a finite number: the row of a sensor that failed is left out, not written as NaN"
                }
                Form::Columns => {
                    "a reading is a finite number: NaN stands for no fix, in a fix's columns only"
                }
            };
            return Err(Problem::new(format!("the reading is {v}"), help));
        }
        if let Column::Position(a) = c {
            self.fix_cells[a] = Some(true);
        }
        c.set(&mut self.sample, Some(v));
        Ok(())
    }

    /// The row read: a position fix whole or absent, the time the next
    /// sensor instant. An error gives the cell it is at.
    fn end_row(&mut self) -> Result<(), (usize, Problem)> {
        let file = self.form == Form::File;
        if self.fix_cells.iter().any(|f| *f != self.fix_cells[0]) {
            let k = self
                .order
                .iter()
                .position(|c| matches!(c, Column::Position(_)))
                .unwrap_or(0);
            let none = if file {
                "three empty cells"
            } else {
                "NaN in all three"
            };
            return Err((
                k,
                Problem::new(
                    "a position fix has some of fix_X, fix_Y, fix_Z and not the others",
                    format!("a position fix gives all three coordinates, or none ({none})"),
                ),
            ));
        }
        if self.fix_cells[0] != Some(true) {
            self.sample.position = None;
        }
        let t = self.sample.t;
        let at_t = self.time_cell();
        if let Some(prev) = self.samples.last()
            && t <= prev.t
        {
            let (previous, help) = if file {
                (
                    "row's",
                    "the rows' times increase, one row per sensor instant",
                )
            } else {
                (
                    "instant's",
                    "the times increase, one element per sensor instant",
                )
            };
            return Err((
                at_t,
                Problem::new(
                    format!(
                        "t = {t} does not follow the previous {previous} t = {}",
                        prev.t
                    ),
                    help,
                ),
            ));
        }
        let k = self.samples.len();
        let period = 1.0 / self.config.rate;
        let want = k as f64 * period;
        if (t - want).abs() > SAME_INSTANT * (1.0 + want.abs()) {
            let rate = self.config.rate;
            let check = "check that [sensors] rate is the one the log was written with";
            let (instant, help) = if file {
                (
                    format!("the sensor instant of row {}", k + 1),
                    format!(
                        "row k of a sensor log is at t = (k − 1) / rate from t = 0, every {period} s with none missing; {check}"
                    ),
                )
            } else {
                (
                    format!("sensor instant {k}"),
                    format!(
                        "element k of `t` is at t = k / rate from t = 0, every {period} s with none missing; {check}"
                    ),
                )
            };
            return Err((
                at_t,
                Problem::new(
                    format!("t = {t} is not {instant} at rate = {rate} Hz: t = {want}"),
                    help,
                ),
            ));
        }
        self.samples.push(std::mem::take(&mut self.sample));
        Ok(())
    }
}

/// What to say of a header name that is not a column of the declaration:
/// a column of a sensor not declared, of a wheel or coordinate the rover
/// does not have, or no sensor column at all.
fn undeclared(
    name: &str,
    config: &SensorConfig,
    wheels: usize,
    coordinates: usize,
    listing: &str,
) -> (String, String) {
    let help = format!("the columns of this declaration are {listing}");
    let Some(c) = Column::from_name(name) else {
        return (format!("`{name}` is no sensor column"), help);
    };
    let problem = match c {
        Column::WheelAngle(j) | Column::Torque(j) | Column::Steering(j) if j >= wheels => {
            format!("the rover has {wheels} wheels: there is no wheel {}", j + 1)
        }
        Column::Suspension(i) if i >= coordinates => format!(
            "the rover has {coordinates} suspension coordinates: there is no coordinate {}",
            i + 1
        ),
        c => {
            let declared = match c {
                Column::Gyro(_) | Column::Accel(_) => config.imu.is_some(),
                Column::WheelAngle(_) => config.wheel_encoders.is_some(),
                Column::Suspension(_) => config.suspension_encoders.is_some(),
                Column::Position(_) => config.position_fix.is_some(),
                Column::Heading => config.heading_fix.is_some(),
                _ => true,
            };
            if declared {
                return (format!("`{name}` does not fit the declaration"), help);
            }
            return (
                format!(
                    "the column is read by {}, which [sensors] does not declare",
                    sensor_of(&c)
                ),
                format!(
                    "declare [sensors.{}] (the declaration the log was written with), or read the log without that column: {listing}",
                    table_of(&c)
                ),
            );
        }
    };
    (problem, help)
}

/// The sensor that reads column `c`, in words.
fn sensor_of(c: &Column) -> &'static str {
    match c {
        Column::Gyro(_) | Column::Accel(_) => "an IMU",
        Column::WheelAngle(_) => "wheel encoders",
        Column::Suspension(_) => "suspension encoders",
        Column::Position(_) => "a position fix",
        Column::Heading => "a heading fix",
        Column::Time | Column::Torque(_) | Column::Steering(_) => "every log",
    }
}

/// The `[sensors]` table that declares the sensor of column `c`.
fn table_of(c: &Column) -> &'static str {
    match c {
        Column::Gyro(_) | Column::Accel(_) => "imu",
        Column::WheelAngle(_) => "wheel_encoders",
        Column::Suspension(_) => "suspension_encoders",
        Column::Position(_) => "position_fix",
        Column::Heading => "heading_fix",
        Column::Time | Column::Torque(_) | Column::Steering(_) => "",
    }
}

/// Why a log of the declaration has column `c`.
fn declared_by(c: &Column) -> String {
    match c {
        Column::Time | Column::Torque(_) | Column::Steering(_) => {
            "every sensor log has (the time and the commands)".into()
        }
        c => format!(
            "[sensors.{}] declares ({} reads it)",
            table_of(c),
            sensor_of(c)
        ),
    }
}
