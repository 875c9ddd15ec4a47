//! Scenario files: what a run does. TOML, every table
//! `deny_unknown_fields`, SI units, `*_deg` where degrees are accepted.
//!
//! ```toml
//! rover = "exomars"          # a built-in name or a file, relative to this file
//! duration = 40.0            # \[s\], settling included
//! settle = 6.0               # \[s\] commands held at zero first (the paper's settling)
//! output_rate = 20.0         # \[Hz\]
//!
//! [terrain]                  # see docs/TERRAIN.md; default flat
//! kind = "random"
//! z_r = 0.2
//! soil = "lunar_nominal"     # optional: soft ground (docs/SOIL.md)
//!
//! [control.speed]
//! speed = 0.05               # [m/s], or { points = [[0, 0.05], [20, 0.1]] }
//! [control.steering]
//! kind = "ackermann"         # or "slip" (delta_tau), or "heading" (heading_deg,
//! front_left_deg = 5.0       # kp, ki, kd; or via = "ackermann", lookahead;
//!                            # cross_track, cross_track_integral, line_origin
//!                            # or waypoints)
//! [control.commands]         # optional: open-loop torques/steering from a CSV file
//! file = "drive.csv"         # header t,tau1,…,delta1,…; relative to this file
//!
//! [integrator.bdf]            # the default: orders 1–2, like ode15s
//! rtol = 1e-4                # the default; `atol` (m, rad, m/s, rad/s alike)
//!                            # replaces the per-component absolute tolerances
//!
//! [sensors]                   # optional: sensors.csv beside run.csv (docs/ESTIMATE.md)
//! seed = 1
//! rate = 100.0               # [Hz]: the IMU and the encoders
//! [sensors.imu]
//! gyro_noise_deg_per_sqrt_h = 0.2
//! gyro_bias_deg_per_h = 10.0
//! accel_noise_ug_per_sqrt_hz = 100.0
//! accel_bias_mg = 0.1
//! [sensors.wheel_encoders]
//! resolution = 0.001         # [rad]
//! [sensors.position_fix]     # also [sensors.suspension_encoders], [sensors.heading_fix]
//! rate = 0.1
//! sigma = 0.05
//!
//! [output]
//! mcap = true                # run.mcap beside run.csv (docs/VIEW.md)
//! ```

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::ground::GroundConfig;
use rover_dynamics::contact::RimSampling;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_integrate::{BdfConfig, IntegratorConfig};
use rover_runtime::control::ControllerConfig;
use rover_runtime::wheel_law::WheelLawConfig;

/// A whole scenario.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scenario {
    /// The rover: a built-in name or a description file (relative to the
    /// scenario file). The command line's rover argument overrides it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rover: Option<String>,
    /// Simulated time \[s\], settling included; > 0.
    pub duration: f64,
    /// Settling time \[s\]: commands (speed, steering, Δτ, active suspension)
    /// stay at zero until then, so the rover comes to rest on its wheels.
    #[serde(default)]
    pub settle: f64,
    /// Output rows per second \[Hz\]; > 0.
    #[serde(default = "default_rate")]
    pub output_rate: f64,
    /// No ground at all (free flight): the terrain is ignored.
    #[serde(default)]
    pub free_flight: bool,
    /// The ground: its shape, and its soil if it is soft.
    #[serde(default)]
    pub terrain: GroundConfig,
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
    /// |roll| or |pitch| beyond this stops the run as a roll-over \[deg\].
    #[serde(default = "default_rollover")]
    pub rollover_limit_deg: f64,
    /// Model fidelity (MODEL.md §9): `"full"` (default), `"simplified"`,
    /// `"linearized"`, `"linearized_exact_rotation"` or `"quasi_static"`.
    #[serde(default)]
    pub fidelity: FidelityLevel,
    /// Quasi-static runs with slip steering follow a path: the CSV of
    /// another run (relative to this file) whose X, Y, ψ are imposed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub path_from: Option<PathBuf>,
    /// Time the parts of every right-hand side (wheels, contact search, wheel
    /// law, plant) and report them, with the integrator's and the output's
    /// share, in the summary's `profile` (default false; reading the clock
    /// costs a few percent of the run).
    #[serde(default)]
    pub profile: bool,
    /// The rover's sensors (`[sensors]`, docs/ESTIMATE.md): their readings
    /// go to `sensors.csv`, and the run lands on their instants.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sensors: Option<rover_estimate::SensorConfig>,
    /// What a run writes besides run.csv and summary.json (`[output]`).
    #[serde(default)]
    pub output: OutputConfig,
}

/// The `[output]` table: the files a run writes besides run.csv and
/// summary.json.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputConfig {
    /// `run.mcap` beside run.csv: the run as an MCAP log of Foxglove
    /// messages (docs/VIEW.md), as `rover simulate --mcap` writes it.
    #[serde(default)]
    pub mcap: bool,
}

/// The four fidelity levels of MODEL.md §9.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FidelityLevel {
    /// Level 1: the full nonlinear model.
    #[default]
    Full,
    /// Level 2: T_j frozen at rest, M constant.
    Simplified,
    /// Level 3, the paper's: linear kinematics, R, E⁻¹ and the gravity
    /// direction to first order in roll and pitch, no f1.
    Linearized,
    /// Level 3 keeping R exact (only gravity and E⁻¹ to first order).
    LinearizedExactRotation,
    /// Level 4: static equilibrium along an imposed path.
    QuasiStatic,
}

impl FidelityLevel {
    /// The dynamic level, None for quasi-static.
    pub fn dynamic(self) -> Option<rover_dynamics::fidelity::Fidelity> {
        use rover_dynamics::fidelity::Fidelity;
        match self {
            FidelityLevel::Full => Some(Fidelity::Full),
            FidelityLevel::Simplified => Some(Fidelity::Simplified),
            FidelityLevel::Linearized => Some(Fidelity::Linearized),
            FidelityLevel::LinearizedExactRotation => Some(Fidelity::LinearizedExactRotation),
            FidelityLevel::QuasiStatic => None,
        }
    }
}

/// Most rim samples `contact.samples` accepts (0.018° apart).
pub const MAX_CONTACT_SAMPLES: usize = 10_000;
/// Most output rows a run writes (duration × output_rate + 1), a few GB of
/// CSV for the largest rovers.
pub const MAX_OUTPUT_ROWS: u64 = 1_000_000;
/// Most steps a fixed-step method takes over a run (duration / step), or an
/// adaptive one at least takes under its `max_step`.
pub const MAX_STEPS: u64 = 100_000_000;
/// Farthest a run may start from the origin \[m\] (three Mars radii):
/// within it a double holds positions to 2 nm.
pub const MAX_POSITION: f64 = 1e7;

fn default_rate() -> f64 {
    20.0
}
fn default_rollover() -> f64 {
    80.0
}
/// The integrator of a scenario without `[integrator]`: BDF/NDF of orders
/// 1–2, like the paper's ode15s, at BDF's default tolerances (rtol 1e-4
/// and the rover's error scales per state component,
/// `rover_runtime::sim::ErrorScale`):
/// a rover standing on the ground is stiff (the regularized cornering law
/// is a lateral damper of C/v_ε = 5·10⁴ N·s/m per wheel), which makes an
/// explicit method crawl; orders above 2 are not A-stable and stalled on
/// the active-suspension runs.
pub fn default_integrator() -> IntegratorConfig {
    IntegratorConfig::Bdf(BdfConfig {
        max_order: 2,
        ..BdfConfig::default()
    })
}

/// The `[initial]` table. Missing entries take the rest state: G at the
/// origin, level, suspension at rest, at rest, wheels touching the ground.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InitialState {
    /// X, Y of G \[m\].
    #[serde(default)]
    pub xy: [f64; 2],
    /// Z of G \[m\]; absent: the lowest wheel just touches the ground.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z: Option<f64>,
    /// Roll φ, pitch θ, yaw ψ \[deg\].
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
    /// `"bounded"` (default), `"meridional"` (the rim sampled 1° apart) or
    /// `"tracked"` (docs/TERRAIN.md).
    #[serde(default)]
    pub method: ContactMethod,
    /// Rim samples over the lower half (default 181: 1° apart), for the
    /// sampled search and where the bounded one falls back on it.
    #[serde(default = "default_samples")]
    pub samples: usize,
    /// The wheel law (`{ kind = "chen_genta" }` by default, or `"magic_formula"`).
    #[serde(default)]
    pub law: WheelLawConfig,
    /// Rolling-resistance coefficient C_rr (ours, not the paper's): a force
    /// `C_rr·F_n` against each patch's rolling, on top of either law;
    /// default 0, the paper's law (see [`rover_dynamics::wheel_law::rolling_resistance`]).
    #[serde(default)]
    pub rolling_resistance: f64,
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
            rolling_resistance: 0.0,
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

    /// The ground of this table on `terrain`: search, sampling, law and
    /// rolling resistance.
    pub fn ground<H: rover_dynamics::HeightField>(
        &self,
        terrain: H,
        model: &rover_dynamics::Model,
    ) -> rover_runtime::ground::Ground<H> {
        rover_runtime::ground::Ground::new(terrain, model, self.method, self.sampling(), self.law)
            .with_rolling_resistance(self.rolling_resistance)
    }
}

/// A scenario field that cannot be used: its dotted path, what is wrong
/// and how to fix it.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct FieldError {
    /// The field, as a dotted path (`duration`, `contact.samples`).
    pub field: &'static str,
    /// What is wrong (naming the field) and how to fix it.
    pub message: String,
}

/// A scenario file that cannot be used: the file, where, what, how to fix.
#[derive(Debug, thiserror::Error)]
#[error("{}{}: {message}", file.display(), line.map(|l| format!(":{l}")).unwrap_or_default())]
pub struct ScenarioError {
    /// The scenario file.
    pub file: PathBuf,
    /// The line of a semantic error (parse errors carry their own location).
    pub line: Option<usize>,
    /// What is wrong (with line and column when known) and how to fix it.
    pub message: String,
}

impl Scenario {
    /// Parse and check a scenario file.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        Self::read(path).map(|(scenario, _)| scenario)
    }

    /// Parse and check a scenario file; the scenario and the file's text
    /// (which locates a field that a later message names).
    pub fn read(path: &Path) -> Result<(Self, String), ScenarioError> {
        let error = |line: Option<usize>, message: String| ScenarioError {
            file: path.to_path_buf(),
            line,
            message,
        };
        let text = rover_files::read_text(path, rover_files::Limit::Text).map_err(|e| {
            match rover_files::NotUtf8::of(&e) {
                Some(at) => error(
                    Some(at.line),
                    format!(
                        "column {}: byte {} is not valid UTF-8\n  = help: save the scenario as UTF-8 text (TOML is UTF-8)",
                        at.column,
                        at.byte + 1
                    ),
                ),
                None => error(
                    None,
                    format!(
                        "cannot read the scenario file: {e}\n  = help: give the path of a scenario file (.toml)"
                    ),
                ),
            }
        })?;
        let scenario = Self::parse(&text, path)?;
        Ok((scenario, text))
    }

    /// Parse and check scenario text; `path` names it in messages.
    pub fn parse(text: &str, path: &Path) -> Result<Self, ScenarioError> {
        let s: Scenario = toml::from_str(text).map_err(|e| ScenarioError {
            file: path.to_path_buf(),
            line: None,
            message: locate(text, &e),
        })?;
        if let Some((field, v)) = non_finite(&s) {
            return Err(ScenarioError {
                file: path.to_path_buf(),
                line: line_of_field(text, &field),
                message: format!(
                    "{field} = {v}: every number of a scenario must be finite\n  = help: give a finite number in SI units (`max_step = inf` is the one infinity allowed: no limit)"
                ),
            });
        }
        s.check().map_err(|(field, message)| ScenarioError {
            file: path.to_path_buf(),
            // Too many rows at the default rate: the duration's line.
            line: line_of_field(text, field)
                .or_else(|| line_of_field(text, "duration").filter(|_| field == "output_rate")),
            message,
        })?;
        Ok(s)
    }

    /// A scenario of `duration` seconds with every other field at its
    /// default, as a file holding only `duration = …` reads.
    pub fn with_duration(duration: f64) -> Self {
        Scenario {
            rover: None,
            duration,
            settle: 0.0,
            output_rate: default_rate(),
            free_flight: false,
            terrain: GroundConfig::default(),
            initial: InitialState::default(),
            integrator: default_integrator(),
            control: ControllerConfig::default(),
            contact: ContactConfig::default(),
            rollover_limit_deg: default_rollover(),
            fidelity: FidelityLevel::default(),
            path_from: None,
            profile: false,
            sensors: None,
            output: OutputConfig::default(),
        }
    }

    /// Whether the rover drives on a soil (a `[terrain]` soil, and ground
    /// under it): its wheels then spin as states, and its rows carry their
    /// spin, slip and sinkage.
    pub fn soft(&self) -> bool {
        self.terrain.is_soft() && !self.free_flight
    }

    /// The checks that need no rover, which a scenario file gets when it
    /// is read: the error names the field and says how to fix it.
    pub fn validate(&self) -> Result<(), FieldError> {
        self.check()
            .map_err(|(field, message)| FieldError { field, message })
    }

    /// Checks that need no rover; the error names the field.
    fn check(&self) -> Result<(), (&'static str, String)> {
        let positive = |key: &'static str, v: f64, help: &str| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err((key, format!("{key} must be > 0, got {v}\n  = help: {help}")))
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
            return Err((
                "settle",
                format!(
                    "settle must lie in [0, duration] = [0, {}] s, got {}\n  = help: the settling time is part of the run",
                    self.duration, self.settle
                ),
            ));
        }
        if !(self.rollover_limit_deg > 0.0 && self.rollover_limit_deg < 90.0) {
            return Err((
                "rollover_limit_deg",
                format!(
                    "rollover_limit_deg must lie in (0, 90), got {}\n  = help: the attitude is singular at 90° of roll (MODEL.md §1)",
                    self.rollover_limit_deg
                ),
            ));
        }
        let c_rr = self.contact.rolling_resistance;
        if !(c_rr.is_finite() && (0.0..1.0).contains(&c_rr)) {
            return Err((
                "contact.rolling_resistance",
                format!(
                    "contact.rolling_resistance must lie in [0, 1), got {c_rr}\n  = help: a coefficient of rolling resistance, C_rr = force / normal load (0.05–0.3 on loose soil)"
                ),
            ));
        }
        if !(3..=MAX_CONTACT_SAMPLES).contains(&self.contact.samples) {
            return Err((
                "contact.samples",
                format!(
                    "contact.samples must lie in [3, {MAX_CONTACT_SAMPLES}], got {}\n  = help: the rim samples over the lower half of each wheel; the default 181 places them 1° apart",
                    self.contact.samples
                ),
            ));
        }
        let rows = (self.duration * self.output_rate).floor() + 2.0;
        if rows.is_nan() || rows > MAX_OUTPUT_ROWS as f64 {
            return Err((
                "output_rate",
                format!(
                    "duration × output_rate = {} s × {} Hz asks for {rows:.3e} output rows; at most {MAX_OUTPUT_ROWS} are written\n  = help: lower output_rate (rows per second) or shorten duration",
                    self.duration, self.output_rate
                ),
            ));
        }
        self.check_anti_spin()?;
        self.check_steps()?;
        self.check_sensors()?;
        self.check_initial()
    }

    /// The `[sensors]` table: its own checks, at most [`MAX_OUTPUT_ROWS`]
    /// rows of readings, and a run with dynamics to read.
    fn check_sensors(&self) -> Result<(), (&'static str, String)> {
        let Some(sensors) = &self.sensors else {
            return Ok(());
        };
        sensors.check().map_err(|e| (e.field, e.message))?;
        let rows = (self.duration * sensors.rate).floor() + 1.0;
        if rows > MAX_OUTPUT_ROWS as f64 {
            return Err((
                "sensors.rate",
                format!(
                    "duration × sensors.rate = {} s × {} Hz asks for {rows:.3e} rows of readings; at most {MAX_OUTPUT_ROWS} are written\n  = help: lower sensors.rate or shorten duration",
                    self.duration, sensors.rate
                ),
            ));
        }
        if self.fidelity == FidelityLevel::QuasiStatic {
            return Err((
                "sensors",
                "[sensors] needs the rover's accelerations and wheel spins, which the quasi-static level (a static equilibrium at each instant) does not have\n  = help: run the sensors at the \"full\", \"simplified\" or \"linearized\" level, or remove [sensors]".into(),
            ));
        }
        Ok(())
    }

    /// The anti-spin distribution reads each wheel's slip, which only a
    /// soil's law gives (the rigid law's tyre rolls without slip).
    fn check_anti_spin(&self) -> Result<(), (&'static str, String)> {
        let anti_spin = self
            .control
            .speed
            .as_ref()
            .is_some_and(|s| s.distribution == rover_runtime::control::Distribution::AntiSpin);
        if anti_spin && !self.soft() {
            return Err((
                "control.speed.distribution",
                "control.speed.distribution = \"anti_spin\" reads each wheel's longitudinal slip, which only a soil gives; this scenario's ground is rigid (its wheels roll without slip)\n  = help: give the terrain a soil (`[terrain] soil = \"dry_sand\"`, docs/SOIL.md), or on rigid ground use distribution = \"measured_load\" (wheels that lose their load lose their torque)".into(),
            ));
        }
        Ok(())
    }

    /// The number of steps a fixed-step method takes (or an adaptive one
    /// at least takes under its `max_step`): at most [`MAX_STEPS`].
    fn check_steps(&self) -> Result<(), (&'static str, String)> {
        use rover_integrate::IntegratorConfig as I;
        let (field, step, what): (&'static str, f64, &str) = match &self.integrator {
            I::Rk4(c) => ("integrator.rk4.step", c.step, "step"),
            I::SemiImplicitEuler(c) => ("integrator.semi_implicit_euler.step", c.step, "step"),
            I::Ros2(c) => ("integrator.ros2.step", c.step, "step"),
            I::Dopri5(c) => ("integrator.dopri5.max_step", c.max_step, "max_step"),
            I::Bdf(c) => ("integrator.bdf.max_step", c.max_step, "max_step"),
        };
        // Each update of the active suspension is a breakpoint of the
        // integration: as many steps at least.
        if let Some(a) = &self.control.active_suspension {
            let updates = self.duration / a.sample_time;
            if a.sample_time > 0.0 && updates > MAX_STEPS as f64 {
                return Err((
                    "control.active_suspension.sample_time",
                    format!(
                        "control.active_suspension.sample_time = {:e} s makes {updates:.3e} updates over duration = {} s; at most {MAX_STEPS} are allowed\n  = help: an active suspension updates every 1e-3 to 0.1 s",
                        a.sample_time, self.duration
                    ),
                ));
            }
        }
        // Non-positive or NaN values are the integrator's own check.
        if step.is_nan() || step <= 0.0 {
            return Ok(());
        }
        let steps = self.duration / step;
        if steps > MAX_STEPS as f64 {
            return Err((
                field,
                format!(
                    "{field} = {step:e} s takes {steps:.3e} steps over duration = {} s; at most {MAX_STEPS} are allowed\n  = help: a rover needs steps of 1e-5 to 1e-3 s: {what} = 1e-4 takes {:.0} steps here",
                    self.duration,
                    self.duration / 1e-4
                ),
            ));
        }
        Ok(())
    }

    /// The `[initial]` numbers: finite, within reach of the origin, and an
    /// attitude inside the roll-over limit.
    fn check_initial(&self) -> Result<(), (&'static str, String)> {
        let i = &self.initial;
        let fields: [(&'static str, &[f64]); 6] = [
            ("initial.xy", &i.xy),
            ("initial.z", i.z.as_slice()),
            ("initial.attitude_deg", &i.attitude_deg),
            ("initial.velocity", &i.velocity),
            ("initial.angular_velocity", &i.angular_velocity),
            (
                "initial.suspension_rates",
                i.suspension_rates.as_deref().unwrap_or(&[]),
            ),
        ];
        for (field, values) in fields {
            if let Some(v) = values.iter().find(|v| !v.is_finite()) {
                return Err((
                    field,
                    format!(
                        "{field}: every number must be finite, got {v}\n  = help: give finite numbers in SI units (m, deg, m/s, rad/s)"
                    ),
                ));
            }
        }
        for (field, values) in [("initial.xy", &i.xy[..]), ("initial.z", i.z.as_slice())] {
            if let Some(v) = values.iter().find(|v| v.abs() > MAX_POSITION) {
                return Err((
                    field,
                    format!(
                        "{field}: {v:e} m is farther than {MAX_POSITION:e} m from the origin, where positions lose their precision\n  = help: place the rover near the origin of its terrain"
                    ),
                ));
            }
        }
        let [roll, pitch, _] = i.attitude_deg;
        if roll.abs() > self.rollover_limit_deg || pitch.abs() > self.rollover_limit_deg {
            return Err((
                "initial.attitude_deg",
                format!(
                    "initial.attitude_deg: roll {roll}° and pitch {pitch}° must both lie within the roll-over limit ±{}°: the run would stop as a roll-over at once\n  = help: start the rover upright, or raise rollover_limit_deg (below 90)",
                    self.rollover_limit_deg
                ),
            ));
        }
        Ok(())
    }
}

/// The first number of `scenario` (its dotted field path and value) that
/// is NaN or infinite: such a gain or set-point would reach the run and
/// its outputs as NaN. An infinite `max_step` (no limit) is allowed.
fn non_finite(scenario: &Scenario) -> Option<(String, f64)> {
    fn walk(v: &toml::Value, path: &str) -> Option<(String, f64)> {
        match v {
            toml::Value::Float(x) => {
                let no_limit = path.ends_with("max_step") && *x == f64::INFINITY;
                (!x.is_finite() && !no_limit).then(|| (path.to_string(), *x))
            }
            toml::Value::Array(items) => items.iter().find_map(|i| walk(i, path)),
            toml::Value::Table(t) => t.iter().find_map(|(k, v)| {
                let p = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                walk(v, &p)
            }),
            _ => None,
        }
    }
    walk(&toml::Value::try_from(scenario).ok()?, "")
}

/// Longest source line echoed in an error (characters).
const ECHO_WIDTH: usize = 160;

/// The toml error with its line/column and caret (toml's own rendering,
/// long lines cut to [`ECHO_WIDTH`] characters), then how to fix it.
fn locate(text: &str, e: &toml::de::Error) -> String {
    // A value inside a table read through a buffer, or nesting too deep:
    // located here (crate::locate), rendered as toml renders.
    let refined = rover_spec::nesting_error(text, e).or_else(|| crate::locate::refine(text, e));
    let (rendered, message) = match &refined {
        Some((span, message)) => (
            crate::locate::render(text, span.clone(), message),
            message.as_str(),
        ),
        None => (e.to_string(), e.message()),
    };
    let mut out = String::new();
    for line in rendered.trim_end().lines() {
        // The source echo (`12 | …`) and its caret line (`   |  ^^^`).
        let gutter = line
            .trim_start()
            .trim_start_matches(|c: char| c.is_ascii_digit());
        let echo = gutter.starts_with('|') || gutter.starts_with(" |");
        if echo && line.chars().count() > ECHO_WIDTH {
            out.extend(line.chars().take(ECHO_WIDTH));
            out.push_str(" …");
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    let help = if message.contains("wanted exactly 1 element") {
        "give exactly one method table, e.g. `[integrator.bdf]` or `[integrator.rk4]`, not two"
    } else if message.starts_with("nesting deeper") {
        "the file nests arrays or tables too deeply for a scenario: a scenario's tables are at most a few levels deep"
    } else if message.contains("unknown field") {
        "remove or correct the key: the fields each table accepts are listed in the message and in the doc of rover-scenario/src/scenario.rs"
    } else {
        "a scenario is TOML: its tables and fields are in the doc of rover-scenario/src/scenario.rs (docs/CLI.md, Files)"
    };
    format!("{out}  = help: {help}")
}

/// 1-based line where the dotted field `path` (e.g. `control.speed.kp`,
/// `terrain.angle_deg`) is written: the key inside its table, else the
/// deepest table header of the path. None when the field is not in the text
/// (a default).
pub fn line_of_field(text: &str, path: &str) -> Option<usize> {
    let parts: Vec<&str> = path.split('.').collect();
    let mut table: Vec<String> = Vec::new();
    let mut best: Option<(usize, usize)> = None; // (matched depth, line)
    for (i, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        if let Some(h) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
            table = h
                .trim_matches(|c| c == '[' || c == ']')
                .split('.')
                .map(|p| p.trim().to_string())
                .collect();
            let depth = table
                .iter()
                .zip(&parts)
                .take_while(|(a, b)| a == *b)
                .count();
            if depth == table.len() && depth > best.map_or(0, |b| b.0) {
                best = Some((depth, i + 1));
            }
            continue;
        }
        let Some((key, _)) = line.split_once('=') else {
            continue;
        };
        let mut full: Vec<&str> = table.iter().map(String::as_str).collect();
        full.extend(key.trim().split('.').map(str::trim));
        let depth = full.iter().zip(&parts).take_while(|(a, b)| a == b).count();
        if depth == full.len() && depth > best.map_or(0, |b| b.0) {
            best = Some((depth, i + 1));
        }
    }
    best.map(|b| b.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The check for non-finite numbers sees every table: each shipped
    /// scenario converts to a TOML value whole, and a NaN put into any of
    /// its numbers is found there by its dotted path.
    #[test]
    fn every_number_of_every_shipped_scenario_is_checked_for_finiteness() {
        let dir = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../scenarios"));
        let mut checked = 0;
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_none_or(|e| e != "toml") {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            let scenario = Scenario::parse(&text, &path).unwrap();
            assert!(
                toml::Value::try_from(&scenario).is_ok(),
                "{}",
                path.display()
            );
            assert_eq!(non_finite(&scenario), None);
            checked += 1;
        }
        assert!(checked >= 10);
        let mut s = Scenario::with_duration(1.0);
        s.initial.velocity[1] = f64::NAN;
        let (field, v) = non_finite(&s).unwrap();
        assert_eq!(field, "initial.velocity");
        assert!(v.is_nan());
        s.initial.velocity[1] = 0.0;
        s.control.speed = Some(rover_runtime::control::SpeedConfig {
            kp: f64::INFINITY,
            ..toml::from_str("speed = 0.1").unwrap()
        });
        assert_eq!(non_finite(&s).unwrap().0, "control.speed.kp");
    }
}
