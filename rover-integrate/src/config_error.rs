//! A bad integrator setting.

use std::fmt;

/// An integrator setting out of range. The message names the method and the field, the value
/// given, the valid range and a typical value; the scenario loader adds the file location.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigError {
    /// Method name as written in a scenario file (`rk4`, `dopri5`, …).
    pub method: &'static str,
    /// Field name as written in a scenario file (`rtol`, `step`, …).
    pub field: &'static str,
    /// The value given, formatted.
    pub value: String,
    /// What is wrong, phrased to follow the field name ("must be > 0").
    pub problem: &'static str,
    /// What to write instead.
    pub hint: &'static str,
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "integrator `{}`: `{}` {}, got {}; {}",
            self.method, self.field, self.problem, self.value, self.hint
        )
    }
}

impl std::error::Error for ConfigError {}
