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

/// A command file that cannot be used: `path:line: problem`, and the fix,
/// in the terrain files' format (line 0: the file as a whole).
fn located(path: &Path, line: usize, problem: impl std::fmt::Display, help: &str) -> String {
    FileError {
        path: path.to_path_buf(),
        place: if line > 0 {
            Place::Line(line)
        } else {
            Place::Whole
        },
        problem: problem.to_string(),
        help: help.to_string(),
    }
    .to_string()
}

impl CommandSchedule {
    /// Read and check `config.file` (relative to `base_dir`) for `model`.
    pub fn load(config: &CommandsConfig, base_dir: &Path, model: &Model) -> Result<Self, String> {
        let path = base_dir.join(&config.file);
        let text = std::fs::read_to_string(&path).map_err(|e| {
            located(
                &path,
                0,
                format!("cannot read the command file: {e}"),
                "give `file` relative to the scenario file",
            )
        })?;
        Self::parse(&text, &path, model, config.interpolation)
    }

    /// Parse command CSV `text` (`path` names it in errors) for `model`.
    pub fn parse(
        text: &str,
        path: &Path,
        model: &Model,
        interpolation: Interpolation,
    ) -> Result<Self, String> {
        let wheels = model.wheels.len();
        let mut lines = text
            .lines()
            .enumerate()
            .map(|(k, l)| (k + 1, l.trim()))
            .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
        let Some((header_line, header)) = lines.next() else {
            return Err(located(
                path,
                0,
                "the command file is empty",
                "start with a header `t,tau1,…` and one row per instant",
            ));
        };
        let mut names = header.split(',').map(str::trim);
        if names.next() != Some("t") {
            return Err(located(
                path,
                header_line,
                format!("the header must start with `t`, got `{header}`"),
                "a header like `t,tau1,tau2,delta1` names the columns",
            ));
        }
        let mut columns = Vec::new();
        for name in names {
            let (channel, number) = if let Some(n) = name.strip_prefix("tau") {
                (Channel::Torque, n)
            } else if let Some(n) = name.strip_prefix("delta") {
                (Channel::Steering, n)
            } else {
                return Err(located(
                    path,
                    header_line,
                    format!("unknown column `{name}`"),
                    "columns after `t` are `tauJ` (N·m) or `deltaJ` (rad), J the wheel from 1",
                ));
            };
            let wheel = match number.parse::<usize>() {
                Ok(j) if (1..=wheels).contains(&j) => j - 1,
                _ => {
                    return Err(located(
                        path,
                        header_line,
                        format!("column `{name}`: the rover has wheels 1 to {wheels}"),
                        "number the wheels from 1 in the description's order",
                    ));
                }
            };
            if channel == Channel::Steering && !model.wheels[wheel].steerable {
                return Err(located(
                    path,
                    header_line,
                    format!("column `{name}`: wheel {} is not steerable", wheel + 1),
                    "steer only wheels with `steerable = true` in the description",
                ));
            }
            if columns.contains(&(channel, wheel)) {
                return Err(located(
                    path,
                    header_line,
                    format!("column `{name}` appears twice"),
                    "give each command once",
                ));
            }
            columns.push((channel, wheel));
        }
        let (mut times, mut values) = (Vec::new(), Vec::new());
        for (number, line) in lines {
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            if fields.len() != columns.len() + 1 {
                return Err(located(
                    path,
                    number,
                    format!(
                        "{} values, the header names {}",
                        fields.len(),
                        columns.len() + 1
                    ),
                    "give t and one value per column on every row",
                ));
            }
            let mut row = Vec::with_capacity(fields.len());
            for field in &fields {
                match field.parse::<f64>() {
                    Ok(v) if v.is_finite() => row.push(v),
                    _ => {
                        return Err(located(
                            path,
                            number,
                            format!("`{field}` is not a finite number"),
                            "values are plain decimal numbers (SI units: s, N·m, rad)",
                        ));
                    }
                }
            }
            if let Some(&last) = times.last()
                && row[0] <= last
            {
                return Err(located(
                    path,
                    number,
                    format!("t = {} s does not come after t = {last} s", row[0]),
                    "rows are in order of strictly increasing time",
                ));
            }
            times.push(row[0]);
            values.extend_from_slice(&row[1..]);
        }
        if times.is_empty() {
            return Err(located(
                path,
                header_line,
                "the command file has a header but no rows",
                "add one row per instant after the header",
            ));
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
