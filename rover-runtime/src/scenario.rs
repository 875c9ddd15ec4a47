//! Scenario files: what a run does (issue 5). TOML, every table
//! `deny_unknown_fields`, SI units, `*_deg` where degrees are accepted.
//!
//! ```toml
//! rover = "exomars"          # a built-in name or a file, relative to this file
//! duration = 40.0            # [s], settling included
//! settle = 6.0               # [s] commands held at zero first (the paper's settling)
//! output_rate = 20.0         # [Hz]
//!
//! [terrain]                  # see docs/TERRAIN.md; default flat
//! kind = "random"
//! z_r = 0.2
//!
//! [control.speed]
//! speed = 0.05               # [m/s], or { points = [[0, 0.05], [20, 0.1]] }
//! [control.steering]
//! kind = "ackermann"
//! front_left_deg = 5.0
//!
//! [integrator.dopri5]
//! rtol = 1e-6
//! ```

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::contact::RimSampling;
use crate::control::ControllerConfig;
use crate::ground::ContactMethod;
use crate::integrate::{AdaptiveConfig, IntegratorConfig};
use crate::terrain::TerrainConfig;
use crate::wheel_law::WheelLawConfig;

/// A whole scenario.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// The rover: a built-in name or a description file (relative to the
    /// scenario file). The command line's rover argument overrides it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rover: Option<String>,
    /// Simulated time [s], settling included; > 0.
    pub duration: f64,
    /// Settling time [s]: commands (speed, steering, Δτ, active suspension)
    /// stay at zero until then, so the rover comes to rest on its wheels.
    #[serde(default)]
    pub settle: f64,
    /// Output rows per second [Hz]; > 0.
    #[serde(default = "default_rate")]
    pub output_rate: f64,
    /// No ground at all (free flight, issue 3's first use): the terrain is ignored.
    #[serde(default)]
    pub free_flight: bool,
    /// The ground.
    #[serde(default)]
    pub terrain: TerrainConfig,
    /// The initial state.
    #[serde(default)]
    pub initial: InitialState,
    /// The integrator.
    #[serde(default = "default_integrator")]
    pub integrator: IntegratorConfig,
    /// The controllers.
    #[serde(default)]
    pub control: ControllerConfig,
    /// Contact search and wheel law.
    #[serde(default)]
    pub contact: ContactConfig,
    /// |roll| or |pitch| beyond this stops the run as a roll-over [deg].
    #[serde(default = "default_rollover")]
    pub rollover_limit_deg: f64,
}

fn default_rate() -> f64 {
    20.0
}
fn default_rollover() -> f64 {
    80.0
}
/// Dormand–Prince with 1e-6 relative error: the tyre's vertical mode (a few
/// ms) is resolved without the cost of a stiff method.
fn default_integrator() -> IntegratorConfig {
    IntegratorConfig::Dopri5(AdaptiveConfig {
        rtol: 1e-6,
        atol: 1e-8,
        ..AdaptiveConfig::default()
    })
}

/// The `[initial]` table. Missing entries take the rest state: G at the
/// origin, level, suspension at rest, at rest, wheels touching the ground.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialState {
    /// X, Y of G [m].
    #[serde(default)]
    pub xy: [f64; 2],
    /// Z of G [m]; absent: the lowest wheel just touches the ground.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<f64>,
    /// Roll φ, pitch θ, yaw ψ [deg].
    #[serde(default)]
    pub attitude_deg: [f64; 3],
    /// Suspension coordinates y [rad or m]; absent: the rest values.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub suspension: Option<Vec<f64>>,
    /// Velocity of G in body components [m/s].
    #[serde(default)]
    pub velocity: [f64; 3],
    /// Angular velocity Ω in body components [rad/s].
    #[serde(default)]
    pub angular_velocity: [f64; 3],
    /// Suspension rates ẏ [rad/s or m/s]; absent: zero.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub suspension_rates: Option<Vec<f64>>,
}

/// The `[contact]` table.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactConfig {
    /// `"meridional"` (default) or `"tracked"`.
    #[serde(default)]
    pub method: ContactMethod,
    /// Rim samples over the lower half (default 181: 1° apart).
    #[serde(default = "default_samples")]
    pub samples: usize,
    /// The wheel law (`{ kind = "chen_genta" }` by default, or `"magic_formula"`).
    #[serde(default)]
    pub law: WheelLawConfig,
}

fn default_samples() -> usize {
    RimSampling::default().samples
}

impl Default for ContactConfig {
    fn default() -> Self {
        Self {
            method: ContactMethod::default(),
            samples: default_samples(),
            law: WheelLawConfig::default(),
        }
    }
}

impl ContactConfig {
    /// The rim sampling.
    pub fn sampling(&self) -> RimSampling {
        RimSampling {
            samples: self.samples,
            ..RimSampling::default()
        }
    }
}

/// A scenario file that cannot be used: the file, where, what, how to fix.
#[derive(Debug, thiserror::Error)]
#[error("{}: {message}", file.display())]
pub struct ScenarioError {
    /// The scenario file.
    pub file: PathBuf,
    /// What is wrong (with line and column when known) and how to fix it.
    pub message: String,
}

impl Scenario {
    /// Parse and check a scenario file.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|e| ScenarioError {
            file: path.to_path_buf(),
            message: format!("cannot read the scenario file: {e}"),
        })?;
        Self::parse(&text, path)
    }

    /// Parse and check scenario text; `path` names it in messages.
    pub fn parse(text: &str, path: &Path) -> Result<Self, ScenarioError> {
        let bad = |message: String| ScenarioError {
            file: path.to_path_buf(),
            message,
        };
        let s: Scenario = toml::from_str(text).map_err(|e| bad(locate(text, &e)))?;
        s.check(text).map_err(bad)?;
        Ok(s)
    }

    fn check(&self, text: &str) -> Result<(), String> {
        let at = |key: &str| {
            line_of(text, key)
                .map(|l| format!("line {l}: "))
                .unwrap_or_default()
        };
        let positive = |key: &str, v: f64, help: &str| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(format!(
                    "{}{key} must be > 0, got {v}\n  = help: {help}",
                    at(key)
                ))
            }
        };
        positive(
            "duration",
            self.duration,
            "the simulated time in seconds, e.g. duration = 40.0",
        )?;
        positive(
            "output_rate",
            self.output_rate,
            "output rows per second, e.g. output_rate = 20.0",
        )?;
        if !(self.settle.is_finite() && self.settle >= 0.0 && self.settle <= self.duration) {
            return Err(format!(
                "{}settle must lie in [0, duration] = [0, {}] s, got {}\n  = help: the settling time is part of the run",
                at("settle"),
                self.duration,
                self.settle
            ));
        }
        if !(self.rollover_limit_deg > 0.0 && self.rollover_limit_deg < 90.0) {
            return Err(format!(
                "{}rollover_limit_deg must lie in (0, 90), got {}\n  = help: the attitude is singular at 90° of roll (MODEL.md §1)",
                at("rollover_limit_deg"),
                self.rollover_limit_deg
            ));
        }
        if self.contact.samples < 3 {
            return Err(format!(
                "{}contact.samples must be ≥ 3, got {}",
                at("samples"),
                self.contact.samples
            ));
        }
        let i = &self.initial;
        let finite =
            i.xy.iter()
                .chain(&i.attitude_deg)
                .chain(&i.velocity)
                .chain(&i.angular_velocity)
                .chain(i.z.iter());
        if finite.clone().any(|v| !v.is_finite()) {
            return Err(format!(
                "{}initial: every number must be finite",
                at("[initial]")
            ));
        }
        Ok(())
    }
}

/// The toml error with its line/column and caret (toml's own rendering).
fn locate(_text: &str, e: &toml::de::Error) -> String {
    e.to_string().trim_end().to_string()
}

/// 1-based line of the first line starting with `key` (for semantic errors).
fn line_of(text: &str, key: &str) -> Option<usize> {
    text.lines()
        .position(|l| l.trim_start().starts_with(key))
        .map(|i| i + 1)
}
