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
/// all), and row k is at t = k / rate.
pub fn parse_sensor_log(
    text: &str,
    file: &Path,
    config: &SensorConfig,
    wheels: usize,
    coordinates: usize,
) -> Result<Vec<SensorSample>, SensorLogError> {
    let error =
        |line: Option<usize>, column: Option<(usize, String)>, problem: String, help: String| {
            SensorLogError {
                file: file.to_path_buf(),
                line,
                column,
                problem,
                help,
            }
        };
    if let Err(e) = config.check() {
        let (problem, help) = e
            .message
            .split_once("\n  = help: ")
            .unwrap_or((&e.message, ""));
        return Err(error(
            None,
            None,
            format!("the declaration to read it with cannot be used: {problem}"),
            help.into(),
        ));
    }
    let expected = columns(config, wheels, coordinates);
    let names: Vec<String> = expected.iter().map(Column::to_string).collect();
    let listing = names.join(",");
    let mut lines = text.lines().enumerate();
    let Some((_, header)) = lines.next() else {
        return Err(error(
            None,
            None,
            "the file is empty: it has no header".into(),
            format!("a sensor log starts with the header {listing}"),
        ));
    };
    // Where each cell of a row goes.
    let mut order: Vec<Column> = Vec::with_capacity(expected.len());
    for (k, name) in header.split(',').map(str::trim).enumerate() {
        let at = Some((k + 1, name.to_string()));
        let Some(c) = names.iter().position(|n| n == name).map(|i| expected[i]) else {
            let (problem, help) = undeclared(name, config, wheels, coordinates, &listing);
            return Err(error(Some(1), at, problem, help));
        };
        if order.contains(&c) {
            return Err(error(
                Some(1),
                at,
                "the column is named twice".into(),
                format!("name each column once: {listing}"),
            ));
        }
        order.push(c);
    }
    if let Some(missing) = expected.iter().find(|c| !order.contains(c)) {
        return Err(error(
            Some(1),
            None,
            format!("no column `{missing}`, which {}", declared_by(missing)),
            format!("the columns of this declaration are {listing}"),
        ));
    }
    let period = 1.0 / config.rate;
    let mut out: Vec<SensorSample> = Vec::new();
    for (i, row) in lines {
        let line = Some(i + 1);
        let cells: Vec<&str> = row.split(',').collect();
        if cells.len() != order.len() {
            return Err(error(
                line,
                None,
                format!("the row has {} cells, the header {}", cells.len(), order.len()),
                "one cell per column in every row (a shorter last row is a log cut off while it was written)".into(),
            ));
        }
        let mut sample = SensorSample::sized(config, wheels, coordinates);
        let mut fix_cells = [None; 3];
        for (k, (cell, c)) in cells.iter().zip(&order).enumerate() {
            let at = || Some((k + 1, c.to_string()));
            let cell = cell.trim();
            if cell.is_empty() {
                if c.sparse() {
                    c.set(&mut sample, None);
                    if let Column::Position(a) = c {
                        fix_cells[*a] = Some(false);
                    }
                    continue;
                }
                return Err(error(
                    line,
                    at(),
                    "the cell is empty".into(),
                    format!(
                        "every row reads `{c}` ({}); only the fixes' cells may be empty",
                        c.unit()
                    ),
                ));
            }
            let v: f64 = cell.parse().map_err(|_| {
                error(
                    line,
                    at(),
                    format!("`{cell}` is not a number"),
                    format!("a decimal number in {}, e.g. 0.25 or -1.5e-3", c.unit()),
                )
            })?;
            if !v.is_finite() {
                return Err(error(
                    line,
                    at(),
                    format!("the reading is {v}"),
                    "a reading is a finite number: the row of a sensor that failed is left out, not written as NaN".into(),
                ));
            }
            if let Column::Position(a) = c {
                fix_cells[*a] = Some(true);
            }
            c.set(&mut sample, Some(v));
        }
        if fix_cells.iter().any(|f| *f != fix_cells[0]) {
            let k = order
                .iter()
                .position(|c| matches!(c, Column::Position(_)))
                .unwrap_or(0);
            return Err(error(
                line,
                Some((k + 1, order[k].to_string())),
                "a position fix has some of fix_X, fix_Y, fix_Z and not the others".into(),
                "a position fix gives all three coordinates, or none (three empty cells)".into(),
            ));
        }
        if fix_cells[0] != Some(true) {
            sample.position = None;
        }
        let t = sample.t;
        let at_t = order.iter().position(|c| *c == Column::Time).unwrap_or(0);
        let t_cell = || Some((at_t + 1, "t".to_string()));
        if let Some(prev) = out.last()
            && t <= prev.t
        {
            return Err(error(
                line,
                t_cell(),
                format!("t = {t} does not follow the previous row's t = {}", prev.t),
                "the rows' times increase, one row per sensor instant".into(),
            ));
        }
        let k = out.len();
        let want = k as f64 * period;
        if (t - want).abs() > SAME_INSTANT * (1.0 + want.abs()) {
            return Err(error(
                line,
                t_cell(),
                format!(
                    "t = {t} is not the sensor instant of row {} at rate = {} Hz: t = {want}",
                    k + 1,
                    config.rate
                ),
                format!(
                    "row k of a sensor log is at t = (k − 1) / rate from t = 0, every {period} s with none missing; check that [sensors] rate is the one the log was written with"
                ),
            ));
        }
        out.push(sample);
    }
    Ok(out)
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
