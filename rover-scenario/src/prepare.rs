//! A run prepared from what a user names: a rover (a built-in name or a
//! description file) and a scenario (a file or its text), read and checked
//! once, and the plant that runs it. The command line, the Python package,
//! the sweep and the live loop all start here, so that a run from any of
//! them gives the same numbers and the same messages.
//!
//! ```
//! use std::path::Path;
//! use std::sync::atomic::AtomicBool;
//! use rover_scenario::prepare::Prepared;
//!
//! let text = "rover = \"swing4\"\nduration = 1.0\n[control.speed]\nspeed = 0.1\n";
//! let run = Prepared::from_text(None, text, Path::new("<example>"), Path::new("."))?;
//! let mut csv = Vec::new();
//! let summary = run.run(false, &mut csv, &AtomicBool::new(false), |_t| {})?; // `rover simulate`
//! assert!(summary.complete && summary.plant == "generated (rover_models::generated::swing4::Swing4)");
//! let mut stepped = run.stepper(false)?; // Python's `Simulation`
//! stepped.step(10)?;
//! assert_eq!(stepped.time(), 10.0 * stepped.dt());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use rover_dynamics::Model;
use rover_dynamics::fidelity::Fidelity;
use rover_models::BuiltinPlant;
use rover_runtime::GenericPlant;
use rover_runtime::generic_plant::TooLarge;
use rover_runtime::quasi_static::QuasiStaticError;
use rover_spec::{Spec, SpecError};

use crate::output::RowSink;
use crate::output::Summary;
use crate::scenario::{Scenario, ScenarioError, line_of_field};
use crate::simulate::{SetupError, simulate_with_outputs};
use crate::stepper::Stepper;

/// Why a run could not be prepared or could not start.
#[derive(Debug, thiserror::Error)]
pub enum PrepareError {
    /// The rover description is invalid (rendered diagnostics, each headed
    /// `error:`).
    #[error("{0}")]
    Spec(#[from] SpecError),
    /// The scenario file is invalid.
    #[error("{0}")]
    Scenario(#[from] ScenarioError),
    /// Neither the caller nor the scenario names a rover.
    #[error(
        "no rover: give one on the command line or as `rover = \"...\"` in {} (built-in: {})",
        origin.display(),
        builtin_names()
    )]
    NoRover {
        /// The scenario's name in messages.
        origin: PathBuf,
    },
    /// The run could not start: the scenario does not fit the rover.
    #[error("{location}{source}")]
    Setup {
        /// `file:line: ` of the offending field, or `file: `.
        location: String,
        /// The error.
        source: SetupError,
    },
    /// A reduced fidelity level needs the loaded equilibrium, which was
    /// not found.
    #[error("cannot find the loaded equilibrium to freeze a reduced fidelity level at: {0}")]
    Equilibrium(QuasiStaticError),
    /// The loaded equilibrium a reduced level would be frozen at lies
    /// outside a coordinate's travel (the message names it).
    #[error("{0}")]
    OutsideTravel(String),
    /// The rover is larger than the generic plant supports.
    #[error("{0}")]
    TooLarge(#[from] TooLarge),
    /// A sensor log's estimation could not start or could not write.
    #[error("{0}")]
    Estimate(String),
}

impl PrepareError {
    /// Whether the message is already rendered as diagnostics, each headed
    /// `error:` (a description's), so that the caller adds no prefix.
    pub fn is_rendered(&self) -> bool {
        matches!(self, PrepareError::Spec(_))
    }

    /// The message as the command line prints it: rendered diagnostics as
    /// they are, anything else headed `error: `. The Python package raises
    /// exceptions with this same text.
    pub fn user_message(&self) -> String {
        if self.is_rendered() {
            self.to_string()
        } else {
            format!("error: {self}")
        }
    }
}

/// Load a rover by built-in name (`exomars`, `swing4`, `mer`, `lrv`) or by
/// path. Relative paths are taken from `base` (the scenario's directory when
/// the rover is named in a scenario) and then from the working directory.
pub fn load_rover(name_or_path: &str, base: Option<&Path>) -> Result<Spec, SpecError> {
    if let Some(text) = rover_models::builtin(name_or_path) {
        let origin = rover_models::builtin_path(name_or_path).unwrap_or(name_or_path);
        return rover_spec::load_str(text, origin);
    }
    let direct = Path::new(name_or_path);
    let path = match base {
        Some(b) if direct.is_relative() && !direct.exists() => b.join(direct),
        _ => direct.to_path_buf(),
    };
    let spec = rover_spec::load_file(&path);
    // A file that a scenario names may be any file: its errors locate, but
    // never quote it.
    if base.is_some() {
        spec.map_err(SpecError::unquoted)
    } else {
        spec
    }
}

/// The names of the built-in rovers, for messages.
pub fn builtin_names() -> String {
    rover_models::NAMES.join(", ")
}

/// Where a reduced level is frozen (docs/MODEL.md §9): the rover's loaded
/// static equilibrium on flat ground, not the rest configuration
/// (docs/FIDELITY.md says why). Runs and `rover codegen` both freeze here,
/// so a generated reduced plant is the generic one.
pub fn reduced_level_reference(model: &Model) -> Result<Vec<f64>, PrepareError> {
    rover_runtime::quasi_static::flat_ground_equilibrium(model).map_err(PrepareError::Equilibrium)
}

/// [`reduced_level_reference`] of a loaded rover: an equilibrium outside
/// the travel names the coordinate, its suspension and its travel.
pub fn reduced_level_reference_of(spec: &Spec) -> Result<Vec<f64>, PrepareError> {
    reduced_level_reference(&spec.model).map_err(|e| named(spec, e))
}

/// An equilibrium outside the travel, told with the coordinate's and the
/// suspension's names; any other error as it is.
fn named(spec: &Spec, e: PrepareError) -> PrepareError {
    let PrepareError::Equilibrium(QuasiStaticError::OutsideTravel {
        coordinate, value, ..
    }) = &e
    else {
        return e;
    };
    let mut y = spec.model.rest();
    if let Some(v) = y.get_mut(*coordinate) {
        *v = *value;
    }
    let at = "at the static equilibrium on flat ground (where a reduced fidelity level is frozen)";
    match spec.outside_travel(&y, at) {
        Some(m) => PrepareError::OutsideTravel(format!(
            "{m}: the rover rests on a bump stop, beyond the range its kinematics are fitted over\n  = help: stiffen the spring or move its neutral (`stiffness`, `neutral`), or widen the travel (`min`, `max`), or use fidelity \"full\""
        )),
        None => e,
    }
}

/// The generic plant of `model` at `level` (reduced levels frozen at
/// [`reduced_level_reference`]).
pub fn generic_plant(model: &Model, level: Fidelity) -> Result<GenericPlant, PrepareError> {
    let y_ref = match level {
        Fidelity::Full => model.rest(),
        _ => reduced_level_reference(model)?,
    };
    Ok(GenericPlant::with_fidelity_at(
        model.clone(),
        level,
        &y_ref,
    )?)
}

/// The generated plant of the built-in rover `rover` at `level`, where one
/// is generated.
pub fn generated_plant(rover: &str, level: Fidelity) -> Option<BuiltinPlant> {
    match level {
        Fidelity::Full => rover_models::plant(rover),
        Fidelity::Simplified => rover_models::plant_at(rover, "simplified"),
        Fidelity::Linearized => rover_models::plant_at(rover, "linearized"),
        Fidelity::LinearizedExactRotation => None,
    }
}

/// The plant a run takes: a built-in rover's generated plant where one
/// exists at the level, the generic plant otherwise (or when asked for).
/// Each call dispatches with a `match`: no allocation, no virtual call.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Debug)]
pub enum RunPlant {
    /// A built-in rover's generated plant.
    Generated(BuiltinPlant),
    /// The generic plant, interpreting the description.
    Generic(GenericPlant),
}

impl RunPlant {
    /// The plant of `rover` (a built-in name or a path, as named) with
    /// `model` at `level`; `generic` asks for the generic plant even where
    /// a generated one exists.
    pub fn new(
        rover: &str,
        model: &Model,
        level: Fidelity,
        generic: bool,
    ) -> Result<Self, PrepareError> {
        match generated_plant(rover, level).filter(|_| !generic) {
            Some(p) => Ok(RunPlant::Generated(p)),
            None => Ok(RunPlant::Generic(generic_plant(model, level)?)),
        }
    }

    /// What ran, for the summary: `generated (<type>)`, `generic`, or
    /// `generic (<level> level)` at a reduced level.
    pub fn backend(&self) -> String {
        crate::output::plant_label(self)
    }
}

rover_dynamics::forward_plant!(RunPlant { Generated, Generic });

/// A scenario read and its rover loaded: everything a run needs before it
/// writes anything.
#[derive(Clone, Debug)]
pub struct Prepared {
    /// The rover's description.
    pub spec: Spec,
    /// The rover as named (built-in name or path), which picks the plant.
    pub rover: String,
    /// The scenario.
    pub scenario: Scenario,
    /// Where the scenario's relative paths start.
    pub base: PathBuf,
    /// The scenario's name in messages (its path, or a stand-in for text).
    pub origin: PathBuf,
    /// The scenario's text, to locate a field that a message names.
    pub text: String,
}

impl Prepared {
    /// Read the scenario file at `path` (once) and load its rover (`rover`
    /// overrides the scenario's).
    pub fn from_file(rover: Option<&str>, path: &Path) -> Result<Self, PrepareError> {
        let (scenario, text) = Scenario::read(path)?;
        let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Self::new(rover, scenario, text, path, &base)
    }

    /// A scenario given as TOML `text`, named `origin` in messages, its
    /// relative paths taken from `base`.
    pub fn from_text(
        rover: Option<&str>,
        text: &str,
        origin: &Path,
        base: &Path,
    ) -> Result<Self, PrepareError> {
        let scenario = Scenario::parse(text, origin)?;
        Self::new(rover, scenario, text.to_string(), origin, base)
    }

    /// A scenario given as TOML `text` for a rover already loaded (`spec`,
    /// named `rover` as a built-in name or path).
    pub fn with_rover(
        spec: Spec,
        rover: &str,
        text: &str,
        origin: &Path,
        base: &Path,
    ) -> Result<Self, PrepareError> {
        Ok(Self {
            spec,
            rover: rover.to_string(),
            scenario: Scenario::parse(text, origin)?,
            base: base.to_path_buf(),
            origin: origin.to_path_buf(),
            text: text.to_string(),
        })
    }

    fn new(
        rover: Option<&str>,
        scenario: Scenario,
        text: String,
        origin: &Path,
        base: &Path,
    ) -> Result<Self, PrepareError> {
        let rover = rover
            .map(str::to_string)
            .or_else(|| scenario.rover.clone())
            .ok_or_else(|| PrepareError::NoRover {
                origin: origin.to_path_buf(),
            })?;
        let spec = load_rover(&rover, Some(base))?;
        Ok(Self {
            spec,
            rover,
            scenario,
            base: base.to_path_buf(),
            origin: origin.to_path_buf(),
            text,
        })
    }

    /// A run that could not start, located at the scenario's offending
    /// field (`file:line: `) when the error names one.
    pub fn locate(&self, source: SetupError) -> PrepareError {
        let line = source
            .field_path()
            .and_then(|f| line_of_field(&self.text, &f));
        let location = match line {
            Some(l) => format!("{}:{l}: ", self.origin.display()),
            None => format!("{}: ", self.origin.display()),
        };
        PrepareError::Setup { location, source }
    }

    /// The plant of the scenario's fidelity level (the full model for a
    /// quasi-static run, whose plant only places the wheels).
    pub fn plant(&self, generic: bool) -> Result<RunPlant, PrepareError> {
        let level = self.scenario.fidelity.dynamic().unwrap_or_default();
        RunPlant::new(&self.rover, &self.spec.model, level, generic)
            .map_err(|e| named(&self.spec, e))
    }

    /// Run the scenario whole, writing the CSV to `csv`; the summary names
    /// the plant that ran. The readings of `[sensors]` are not written
    /// ([`Prepared::run_with_sensors`]); the rows are the same.
    pub fn run<W: Write>(
        &self,
        generic: bool,
        csv: W,
        interrupt: &AtomicBool,
        progress: impl FnMut(f64),
    ) -> Result<Summary, PrepareError> {
        self.run_with_sensors(generic, csv, None::<std::io::Sink>, interrupt, progress)
    }

    /// [`Prepared::run`], writing the readings of the scenario's
    /// `[sensors]` to `sensors` (`rover simulate`'s `sensors.csv`) when
    /// both are given.
    pub fn run_with_sensors<W: Write, S: Write>(
        &self,
        generic: bool,
        csv: W,
        sensors: Option<S>,
        interrupt: &AtomicBool,
        progress: impl FnMut(f64),
    ) -> Result<Summary, PrepareError> {
        self.run_with_outputs(generic, csv, sensors, None, interrupt, progress)
    }

    /// [`Prepared::run_with_sensors`], handing each row also to `rows`
    /// (`rover simulate --mcap`'s log, [`crate::output::RowSink`]).
    pub fn run_with_outputs<W: Write, S: Write>(
        &self,
        generic: bool,
        csv: W,
        sensors: Option<S>,
        rows: Option<&mut dyn RowSink>,
        interrupt: &AtomicBool,
        progress: impl FnMut(f64),
    ) -> Result<Summary, PrepareError> {
        let plant = self.plant(generic)?;
        let (model, name) = (&self.spec.model, &self.spec.name);
        let (scenario, base) = (&self.scenario, &self.base);
        // Each kind of plant runs its own instance of the run: the right-hand
        // side calls the generated plant without a second dispatch.
        let run = match plant {
            RunPlant::Generated(p) => simulate_with_outputs(
                p, model, name, scenario, base, csv, sensors, rows, interrupt, progress,
            ),
            RunPlant::Generic(p) => simulate_with_outputs(
                p, model, name, scenario, base, csv, sensors, rows, interrupt, progress,
            ),
        };
        run.map_err(|e| self.locate(e))
    }

    /// The scenario's run, step by step.
    pub fn stepper(&self, generic: bool) -> Result<Stepper<RunPlant>, PrepareError> {
        Stepper::new(
            self.plant(generic)?,
            &self.spec.model,
            &self.scenario,
            &self.base,
        )
        .map_err(|e| self.locate(e))
    }
}
