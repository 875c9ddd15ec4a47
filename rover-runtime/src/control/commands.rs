//! Open-loop command schedules: per-wheel motor torques and steering angles
//! against time, read from a CSV file — a field test's telemetry replayed
//! on the model, a manoeuvre designed elsewhere. They are added to what the
//! built-in loops command, as [`RoverSystem::set_torques`] and
//! [`RoverSystem::set_steering`] are (and limited to the motors' torque).
//!
//! ```text
//! # comment lines start with '#'; blank lines are ignored
//! t,tau1,tau2,tau3,tau4,delta1,delta2      header: t, then any of tauJ [N·m] and deltaJ [rad]
//! 0.0,0.5,0.5,0.5,0.5,0.0,0.0              one row per instant, t [s] after settling, increasing
//! 2.0,0.5,0.5,0.5,0.5,0.1,0.1
//! ```
//! Wheels are numbered from 1 in the description's order; a wheel without
//! a column gets no command, `deltaJ` needs a steerable wheel. Between rows
//! the values are held (`interpolation = "step"`, the default: each row
//! time is a breakpoint where the integrator restarts) or interpolated
//! linearly; before the first row and while settling there is no command,
//! after the last row its values are held.
//!
//! [`RoverSystem::set_torques`]: crate::sim::RoverSystem::set_torques
//! [`RoverSystem::set_steering`]: crate::sim::RoverSystem::set_steering

use std::path::{Path, PathBuf};

use rover_dynamics::Model;
use serde::{Deserialize, Serialize};

use super::profile::Interpolation;
use rover_terrain::{FileError, Place};

/// The `[control.commands]` table of a scenario.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CommandsConfig {
    /// The CSV file of commands, relative to the scenario file.
    pub file: PathBuf,
    /// `"step"` (default: each value held until the next row) or `"linear"`.
    #[serde(default)]
    pub interpolation: Interpolation,
}

/// What a column commands.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Channel {
    Torque,
    Steering,
}

/// A command schedule, loaded and checked against the rover.
#[derive(Clone, Debug, PartialEq)]
pub struct CommandSchedule {
    interpolation: Interpolation,
    /// Row times \[s\] after settling, strictly increasing.
    times: Vec<f64>,
    /// The columns after `t`: channel and wheel (0-based).
    columns: Vec<(Channel, usize)>,
    /// The values, row by row.
    values: Vec<f64>,
}

/// A command file that cannot be used: the file, the line and what is
/// wrong there. Shown as `path:line: problem`, then `= help:` and the fix,
/// in the terrain files' format.
#[derive(Debug, thiserror::Error)]
#[error("{}", self.as_file_error())]
pub struct CommandFileError {
    /// The file.
    pub path: PathBuf,
    /// The line, from 1; `None` for the file as a whole.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: CommandFileProblem,
}

impl CommandFileError {
    fn new(path: &Path, line: Option<usize>, problem: CommandFileProblem) -> Self {
        Self {
            path: path.to_path_buf(),
            line,
            problem,
        }
    }

    /// The error in the terrain files' format, with the fix.
    fn as_file_error(&self) -> FileError {
        FileError {
            path: self.path.clone(),
            place: self.line.map_or(Place::Whole, Place::Line),
            problem: self.problem.to_string(),
            help: self.problem.help().to_string(),
        }
    }
}

/// What is wrong with a command file.
#[derive(Debug, thiserror::Error)]
pub enum CommandFileProblem {
    /// The file cannot be read.
    #[error("cannot read the command file: {source}")]
    Unreadable {
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// No header: the file is empty, or only comments.
    #[error("the command file is empty")]
    Empty,
    /// The first line is not a header starting with `t` (not quoted: a
    /// file that fails at its first line may be any file on the machine).
    #[error("the first line is not a header starting with the column `t`")]
    NoTime,
    /// A column that is neither `tauJ` nor `deltaJ`.
    #[error("unknown column `{name}`")]
    UnknownColumn {
        /// The column's name.
        name: String,
    },
    /// A column of a wheel the rover does not have.
    #[error("column `{name}`: the rover has wheels 1 to {wheels}")]
    NoSuchWheel {
        /// The column's name.
        name: String,
        /// The rover's number of wheels.
        wheels: usize,
    },
    /// A steering column of a wheel that does not steer.
    #[error("column `{name}`: wheel {wheel} is not steerable")]
    NotSteerable {
        /// The column's name.
        name: String,
        /// The wheel, from 1.
        wheel: usize,
    },
    /// A column given twice.
    #[error("column `{name}` appears twice")]
    Duplicate {
        /// The column's name.
        name: String,
    },
    /// A row whose number of values is not the header's.
    #[error("{given} values, the header names {columns}")]
    RowLength {
        /// The values on the row.
        given: usize,
        /// The columns of the header, `t` included.
        columns: usize,
    },
    /// A value that is not a finite number.
    #[error("`{value}` is not a finite number")]
    NotFinite {
        /// The value as written.
        value: String,
    },
    /// A row whose time does not come after the previous row's.
    #[error("t = {t} s does not come after t = {previous} s")]
    NotIncreasing {
        /// The row's time \[s\].
        t: f64,
        /// The previous row's time \[s\].
        previous: f64,
    },
    /// A header and no rows.
    #[error("the command file has a header but no rows")]
    NoRows,
}

impl CommandFileProblem {
    /// How to fix it.
    pub fn help(&self) -> &'static str {
        match self {
            Self::Unreadable { .. } => "give `file` relative to the scenario file",
            Self::Empty => "start with a header `t,tau1,…` and one row per instant",
            Self::NoTime => "a header like `t,tau1,tau2,delta1` names the columns",
            Self::UnknownColumn { .. } => {
                "columns after `t` are `tauJ` (N·m) or `deltaJ` (rad), J the wheel from 1"
            }
            Self::NoSuchWheel { .. } => "number the wheels from 1 in the description's order",
            Self::NotSteerable { .. } => {
                "steer only wheels with `steerable = true` in the description"
            }
            Self::Duplicate { .. } => "give each command once",
            Self::RowLength { .. } => "give t and one value per column on every row",
            Self::NotFinite { .. } => "values are plain decimal numbers (SI units: s, N·m, rad)",
            Self::NotIncreasing { .. } => "rows are in order of strictly increasing time",
            Self::NoRows => "add one row per instant after the header",
        }
    }
}

impl CommandSchedule {
    /// Read and check `config.file` (relative to `base_dir`) for `model`.
    pub fn load(
        config: &CommandsConfig,
        base_dir: &Path,
        model: &Model,
    ) -> Result<Self, CommandFileError> {
        let path = base_dir.join(&config.file);
        let text = rover_files::read_text(&path, rover_files::Limit::Data).map_err(|source| {
            CommandFileError::new(&path, None, CommandFileProblem::Unreadable { source })
        })?;
        Self::parse(&text, &path, model, config.interpolation)
    }

    /// Parse command CSV `text` (`path` names it in errors) for `model`.
    pub fn parse(
        text: &str,
        path: &Path,
        model: &Model,
        interpolation: Interpolation,
    ) -> Result<Self, CommandFileError> {
        use CommandFileProblem as P;
        let error = |line: usize, problem: P| CommandFileError::new(path, Some(line), problem);
        let wheels = model.wheels.len();
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(k, l)| (k + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let Some((header_line, header)) = lines.next() else {
            return Err(CommandFileError::new(path, None, P::Empty));
        };
        let mut names = header.split(',').map(str::trim);
        if names.next() != Some("t") {
            return Err(error(header_line, P::NoTime));
        }
        let mut columns = Vec::new();
        for name in names {
            let (channel, number) = if let Some(n) = name.strip_prefix("tau") {
                (Channel::Torque, n)
            } else if let Some(n) = name.strip_prefix("delta") {
                (Channel::Steering, n)
            } else {
                let name = rover_files::excerpt(name, 24);
                return Err(error(header_line, P::UnknownColumn { name }));
            };
            let wheel = match number.parse::<usize>() {
                Ok(j) if (1..=wheels).contains(&j) => j - 1,
                _ => {
                    let name = rover_files::excerpt(name, 24);
                    return Err(error(header_line, P::NoSuchWheel { name, wheels }));
                }
            };
            if channel == Channel::Steering && !model.wheels[wheel].steerable {
                let name = rover_files::excerpt(name, 24);
                let wheel = wheel + 1;
                return Err(error(header_line, P::NotSteerable { name, wheel }));
            }
            if columns.contains(&(channel, wheel)) {
                let name = rover_files::excerpt(name, 24);
                return Err(error(header_line, P::Duplicate { name }));
            }
            columns.push((channel, wheel));
        }
        let (mut times, mut values) = (Vec::new(), Vec::new());
        for (number, line) in lines {
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            if fields.len() != columns.len() + 1 {
                let (given, columns) = (fields.len(), columns.len() + 1);
                return Err(error(number, P::RowLength { given, columns }));
            }
            let mut row = Vec::with_capacity(fields.len());
            for field in &fields {
                match field.parse::<f64>() {
                    Ok(v) if v.is_finite() => row.push(v),
                    _ => {
                        let value = rover_files::excerpt(field, 24);
                        return Err(error(number, P::NotFinite { value }));
                    }
                }
            }
            if let Some(&previous) = times.last()
                && row[0] <= previous
            {
                let t = row[0];
                return Err(error(number, P::NotIncreasing { t, previous }));
            }
            times.push(row[0]);
            values.extend_from_slice(&row[1..]);
        }
        if times.is_empty() {
            return Err(error(header_line, P::NoRows));
        }
        Ok(Self {
            interpolation,
            times,
            columns,
            values,
        })
    }

    /// Add the torque commands at time `tc` after settling to `out` [N·m],
    /// one per wheel. Allocation-free: a binary search finds the row.
    pub fn add_torques(&self, tc: f64, out: &mut [f64]) {
        self.add(tc, Channel::Torque, out);
    }

    /// Add the steering commands at time `tc` after settling to `out`
    /// \[rad\], one per wheel.
    pub fn add_steering(&self, tc: f64, out: &mut [f64]) {
        self.add(tc, Channel::Steering, out);
    }

    fn add(&self, tc: f64, which: Channel, out: &mut [f64]) {
        // Before the first row (or a NaN time): no command.
        if tc.is_nan() || tc < self.times[0] {
            return;
        }
        let width = self.columns.len();
        // The last row at or before tc.
        let k = self.times.partition_point(|&t| t <= tc) - 1;
        let row = |k: usize| &self.values[k * width..(k + 1) * width];
        let next =
            (self.interpolation == Interpolation::Linear && k + 1 < self.times.len()).then(|| {
                (
                    k + 1,
                    (tc - self.times[k]) / (self.times[k + 1] - self.times[k]),
                )
            });
        for (c, &(channel, wheel)) in self.columns.iter().enumerate() {
            if channel != which {
                continue;
            }
            out[wheel] += match next {
                Some((k1, s)) => row(k)[c] + (row(k1)[c] - row(k)[c]) * s,
                None => row(k)[c],
            };
        }
    }

    /// Times after settling at which the commands jump (every row, held
    /// values), for the driver to stop and restart at.
    pub fn breakpoints(&self) -> Vec<f64> {
        match self.interpolation {
            Interpolation::Step => self.times.clone(),
            Interpolation::Linear => Vec::new(),
        }
    }
}
