//! One exported plant, as an FMU instance or a C handle holds it: the
//! scenario's run, its variables, the row at the current time and the
//! inputs last set. Opened from a folder packed by
//! [`crate::resources::pack`]; after that, nothing allocates on the
//! success path.

use std::path::Path;

use rover_scenario::prepare::Prepared;

use crate::resources::{ExportSettings, SCENARIO_FILE};
use crate::run::{Factory, Run};
use crate::variables::{Inputs, Role, Variables};

/// Two times within this fraction of (1 + t) are one instant.
const SAME_INSTANT: f64 = 1e-12;

/// A plant ready to step (see the module's documentation).
pub struct Instance {
    run: Box<dyn Run>,
    /// The exported variables.
    pub vars: Variables,
    /// The export's settings, as packed.
    pub settings: ExportSettings,
    /// The scenario's duration \[s\] (the FMU's default stop time).
    pub duration: f64,
    row: Vec<f64>,
    torques: Vec<f64>,
    steering: Vec<f64>,
    neutrals: Vec<f64>,
    neutral_start: Vec<f64>,
    dirty: bool,
}

impl std::fmt::Debug for Instance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Instance")
            .field("t", &self.run.time())
            .field("variables", &self.vars.list.len())
            .finish()
    }
}

impl Instance {
    /// The plant packed in `dir` (its `scenario.toml`, the rover and
    /// terrain files beside it, `export.toml`), its run built by
    /// `factory`. The message says which file is missing or wrong.
    pub fn open(dir: &Path, factory: Factory) -> Result<Self, String> {
        let settings = ExportSettings::read(dir)?;
        Self::open_with(dir, settings, factory)
    }

    /// [`Instance::open`] with the settings given (the C library's inputs
    /// are always on).
    pub fn open_with(
        dir: &Path,
        settings: ExportSettings,
        factory: Factory,
    ) -> Result<Self, String> {
        let scenario = dir.join(SCENARIO_FILE);
        Self::open_scenario(&scenario, settings, factory)
    }

    /// The plant of the scenario file `scenario` (its rover and files
    /// found as `rover simulate` finds them).
    pub fn open_scenario(
        scenario: &Path,
        settings: ExportSettings,
        factory: Factory,
    ) -> Result<Self, String> {
        let prepared = Prepared::from_file(None, scenario).map_err(|e| e.user_message())?;
        let run = factory(&prepared).map_err(|e| e.user_message())?;
        let vars = Variables::new(&prepared.spec, run.columns(), settings.inputs);
        let model = &prepared.spec.model;
        let neutral_start: Vec<f64> = model.coordinates.iter().map(|c| c.neutral).collect();
        let mut instance = Instance {
            row: vec![0.0; run.columns().len()],
            torques: vec![0.0; model.wheels.len()],
            steering: vec![0.0; model.wheels.len()],
            neutrals: neutral_start.clone(),
            neutral_start,
            dirty: false,
            duration: prepared.scenario.duration,
            run,
            vars,
            settings,
        };
        instance.refresh_row();
        Ok(instance)
    }

    fn refresh_row(&mut self) {
        self.run.row_into(&mut self.row);
    }

    /// Back to t = 0: the initial state, the inputs at their start values.
    pub fn reset(&mut self) {
        self.run.reset();
        self.torques.fill(0.0);
        self.steering.fill(0.0);
        self.neutrals.copy_from_slice(&self.neutral_start);
        self.dirty = false;
        self.refresh_row();
    }

    /// Time \[s\].
    pub fn time(&self) -> f64 {
        self.run.time()
    }

    /// The scenario's output interval \[s\].
    pub fn output_step(&self) -> f64 {
        self.run.output_step()
    }

    /// The row at the current time (`t` first), as the CSV's columns.
    pub fn row(&self) -> &[f64] {
        &self.row
    }

    /// The value of the variable `vr`.
    pub fn get(&self, vr: u32) -> Result<f64, String> {
        let var = self.vars.get(vr).ok_or_else(|| self.unknown(vr))?;
        Ok(match var.role {
            Role::Time => self.row[0],
            Role::Output(k) => self.row[k],
            Role::Torque(j) => self.torques[j],
            Role::Steering(j) => self.steering[j],
            Role::Neutral(i) => self.neutrals[i],
        })
    }

    fn unknown(&self, vr: u32) -> String {
        format!(
            "no variable has value reference {vr}: this model's are {} (modelDescription.xml lists them)",
            self.vars.range()
        )
    }

    /// Set the input `vr` to `value`; it takes effect at the next step.
    pub fn set(&mut self, vr: u32, value: f64) -> Result<(), String> {
        let var = self.vars.get(vr).ok_or_else(|| self.unknown(vr))?;
        if !var.is_input() {
            return Err(format!(
                "{} (value reference {vr}) is an output: only inputs can be set{}",
                var.name,
                if self.vars.has_inputs() {
                    ""
                } else {
                    "; this model has none (export it with `--inputs torques`)"
                }
            ));
        }
        if !value.is_finite() {
            return Err(format!(
                "{} (value reference {vr}) set to {value}: give a finite number",
                var.name
            ));
        }
        match var.role {
            Role::Torque(j) => self.torques[j] = value,
            Role::Steering(j) => self.steering[j] = value,
            Role::Neutral(i) => self.neutrals[i] = value,
            Role::Time | Role::Output(_) => unreachable!("checked above"),
        }
        self.dirty = true;
        Ok(())
    }

    /// Set all motor torques [N·m], one per wheel.
    pub fn set_torques(&mut self, torques: &[f64]) -> Result<(), String> {
        self.set_all(torques, "torques", |s| &mut s.torques)
    }

    /// Set all steering angles \[rad\], one per wheel (0 for a wheel that
    /// does not steer).
    pub fn set_steering(&mut self, angles: &[f64]) -> Result<(), String> {
        self.set_all(angles, "steering angles", |s| &mut s.steering)
    }

    /// Set all spring neutrals \[rad or m\], one per suspension coordinate.
    pub fn set_neutrals(&mut self, neutrals: &[f64]) -> Result<(), String> {
        self.set_all(neutrals, "spring neutrals", |s| &mut s.neutrals)
    }

    fn set_all(
        &mut self,
        values: &[f64],
        what: &str,
        field: impl Fn(&mut Self) -> &mut Vec<f64>,
    ) -> Result<(), String> {
        let target = field(self);
        if values.len() != target.len() {
            return Err(format!(
                "{} {what} given, the rover takes {}",
                values.len(),
                target.len()
            ));
        }
        if let Some(k) = values.iter().position(|v| !v.is_finite()) {
            return Err(format!("{what}[{k}] is {}: give finite numbers", values[k]));
        }
        target.copy_from_slice(values);
        self.dirty = true;
        Ok(())
    }

    /// Advance by `step` \[s\] from `current` (the importer's time, which
    /// must be this instance's): the inputs set since the last step take
    /// effect first. A step the integrator cannot take (not finite, not
    /// positive, shorter than the run's time resolution) changes nothing.
    pub fn step(&mut self, current: f64, step: f64) -> Result<(), String> {
        let t = self.run.time();
        if !current.is_finite() || (current - t).abs() > 1e-9 * (1.0 + t.abs()) {
            return Err(format!(
                "a step from t = {current} s, but the plant is at t = {t} s: step from where the last step ended"
            ));
        }
        if !step.is_finite() || step <= SAME_INSTANT * (1.0 + t.abs()) {
            return Err(format!(
                "a communication step of {step} s cannot be taken: give a finite step longer than {:e} s (the scenario's output interval is {} s)",
                SAME_INSTANT * (1.0 + t.abs()),
                self.run.output_step()
            ));
        }
        if let Some(e) = self.run.failure() {
            return Err(format!(
                "the run failed earlier and stays where it failed until reset: {e}"
            ));
        }
        if self.dirty {
            self.run
                .set_commands(&self.torques, &self.steering)
                .map_err(|e| e.to_string())?;
            for i in 0..self.neutrals.len() {
                self.run.set_neutral(i, self.neutrals[i]);
            }
            self.dirty = false;
        }
        let advanced = self.run.advance_to(current + step);
        self.refresh_row();
        advanced.map_err(|e| format!("the step from t = {current} s by {step} s failed: {e}"))
    }

    /// The inputs the plant takes.
    pub fn inputs(&self) -> Inputs {
        self.settings.inputs
    }
}
