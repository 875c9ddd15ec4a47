//! A set-point as a function of time: a constant or a table.

use serde::{Deserialize, Serialize};

/// A scalar set-point against time: a constant, or `[[t, value], …]` held
/// piecewise constant (`"step"`, the default: commands change at instants)
/// or interpolated linearly (`"linear"`, ramps).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(
    untagged,
    expecting = "a number, or a table { points = [[t, value], …], interpolation = \"step\" | \"linear\" }"
)]
pub enum Profile {
    /// The same value at all times.
    Constant(f64),
    /// A table of (time \[s\], value) pairs, times increasing.
    Table {
        /// The (t, value) points.
        points: Vec<[f64; 2]>,
        /// `"step"` (default) or `"linear"`.
        #[serde(default)]
        interpolation: Interpolation,
    },
}

/// How a [`Profile`] table is read between its points.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Interpolation {
    /// Hold each value until the next point.
    #[default]
    Step,
    /// Interpolate linearly; hold the ends.
    Linear,
}

/// A set-point that cannot be used: what is wrong, with its numbers.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum ProfileError {
    /// A constant that is not a finite number.
    #[error("value {0} is not a finite number")]
    NotFinite(f64),
    /// A table without points.
    #[error("the table has no points; give at least one [t, value]")]
    Empty,
    /// A point whose time or value is not finite.
    #[error("point {point} = [{t}, {value}] is not finite")]
    PointNotFinite {
        /// The point, from 1.
        point: usize,
        /// Its time \[s\].
        t: f64,
        /// Its value.
        value: f64,
    },
    /// A point whose time does not come after the previous point's.
    #[error("times must increase: point {point} has t = {t} s after t = {previous} s")]
    NotIncreasing {
        /// The point, from 1.
        point: usize,
        /// Its time \[s\].
        t: f64,
        /// The previous point's time \[s\].
        previous: f64,
    },
}

impl Default for Profile {
    fn default() -> Self {
        Profile::Constant(0.0)
    }
}

impl Profile {
    /// The value at time t \[s\] (before the first point: the first value).
    pub fn at(&self, t: f64) -> f64 {
        match self {
            Profile::Constant(v) => *v,
            Profile::Table {
                points,
                interpolation,
            } => {
                let Some(first) = points.first() else {
                    return 0.0;
                };
                if t <= first[0] {
                    return first[1];
                }
                for w in points.windows(2) {
                    let (a, b) = (w[0], w[1]);
                    if t < b[0] {
                        return match interpolation {
                            Interpolation::Step => a[1],
                            Interpolation::Linear => {
                                a[1] + (b[1] - a[1]) * (t - a[0]) / (b[0] - a[0])
                            }
                        };
                    }
                }
                points[points.len() - 1][1]
            }
        }
    }

    /// The same profile with `f` applied to every value (a unit
    /// conversion, done once).
    pub fn map(&self, f: impl Fn(f64) -> f64) -> Profile {
        match self {
            Profile::Constant(v) => Profile::Constant(f(*v)),
            Profile::Table {
                points,
                interpolation,
            } => Profile::Table {
                points: points.iter().map(|&[t, v]| [t, f(v)]).collect(),
                interpolation: *interpolation,
            },
        }
    }

    /// Times at which the value jumps (step tables), for the driver to stop at.
    pub fn breakpoints(&self) -> Vec<f64> {
        match self {
            Profile::Table {
                points,
                interpolation: Interpolation::Step,
            } => points.iter().map(|p| p[0]).collect(),
            _ => Vec::new(),
        }
    }

    /// Check the table: finite numbers, times strictly increasing. The
    /// error says what to fix.
    pub fn validate(&self) -> Result<(), ProfileError> {
        match self {
            Profile::Constant(v) if !v.is_finite() => Err(ProfileError::NotFinite(*v)),
            Profile::Constant(_) => Ok(()),
            Profile::Table { points, .. } => {
                if points.is_empty() {
                    return Err(ProfileError::Empty);
                }
                for (i, p) in points.iter().enumerate() {
                    if !p[0].is_finite() || !p[1].is_finite() {
                        return Err(ProfileError::PointNotFinite {
                            point: i + 1,
                            t: p[0],
                            value: p[1],
                        });
                    }
                    if i > 0 && p[0] <= points[i - 1][0] {
                        return Err(ProfileError::NotIncreasing {
                            point: i + 1,
                            t: p[0],
                            previous: points[i - 1][0],
                        });
                    }
                }
                Ok(())
            }
        }
    }
}
