//! A run advanced by the caller, one output interval at a time: what a
//! step-wise caller (the Python package's `Simulation`, a learning agent's
//! environment) drives. Between steps it may read the state and change the
//! open-loop commands and the set-points. A step advances through the same
//! [`Driver`] as the whole run ([`rover_runtime::sim::run`]), so that a run
//! stepped without changes gives the rows of the whole run bit for bit.

use std::path::Path;

use rover_dynamics::Model;
use rover_dynamics::plant::Plant;

use crate::scenario::{FidelityLevel, Scenario};
use crate::simulate::{SetupError, run_options, sensor_period, system_of};
use rover_integrate::{AnyIntegrator, Integrator, OdeSystem};
use rover_runtime::control::ControlError;
use rover_terrain::Terrain;

use rover_runtime::row::{Columns, RowInputs};

/// Two times within this fraction of (1 + t) are one instant, as the
/// driver takes them.
const SAME_INSTANT: f64 = 1e-12;
use rover_runtime::sim::{CommandError, Driver, RoverSystem, RunError, RunOptions};

/// A run under the caller's control (see the module's documentation).
#[derive(Clone, Debug)]
pub struct Stepper<P> {
    start: RoverSystem<P, Terrain>,
    sys: RoverSystem<P, Terrain>,
    integ_start: AnyIntegrator,
    integ: AnyIntegrator,
    driver: Driver,
    columns: Columns,
    y0: Vec<f64>,
    y: Vec<f64>,
    scratch: Vec<f64>,
    commands: Vec<f64>,
    t: f64,
    failed: Option<RunError>,
}

impl<P: Plant + Clone> Stepper<P> {
    /// The run of `scenario` with `plant` (whose model is `model`), placed
    /// and settled as [`crate::simulate::simulate`] places it; a step is
    /// one output interval, 1 / `output_rate`. The quasi-static level has
    /// no dynamics to step.
    pub fn new(
        plant: P,
        model: &Model,
        scenario: &Scenario,
        base_dir: &Path,
    ) -> Result<Self, SetupError> {
        if scenario.fidelity == FidelityLevel::QuasiStatic {
            return Err(SetupError::Path(
                "a quasi-static run has no dynamics to step; run it whole".into(),
            ));
        }
        let (sys, y) = system_of(plant, model, scenario, base_dir)?;
        let integ = scenario.integrator.build(sys.dim())?;
        let driver = Driver::new(
            &sys.control,
            RunOptions {
                duration: f64::INFINITY,
                ..run_options(scenario)
            },
        )
        .with_sensor_period(sensor_period(scenario))
        .with_landing(scenario.duration);
        let mut s = Self {
            start: sys.clone(),
            integ_start: integ.clone(),
            scratch: vec![0.0; y.len()],
            commands: vec![0.0; sys.plant.wheel_count()],
            sys,
            integ,
            driver,
            columns: Columns::on_ground(model.m(), model.wheels.len(), scenario.soft()),
            y0: y.clone(),
            y,
            t: 0.0,
            failed: None,
        };
        s.reset();
        Ok(s)
    }

    /// Back to t = 0: the initial state, the scenario's commands and
    /// set-points, a fresh integrator.
    pub fn reset(&mut self) {
        self.sys.clone_from(&self.start);
        self.integ.clone_from(&self.integ_start);
        self.y.copy_from_slice(&self.y0);
        self.t = 0.0;
        self.driver.rewind();
        self.driver
            .start(&mut self.sys, &mut self.integ, self.t, &self.y);
        self.failed = self.refresh().err();
    }

    /// Advance `n` output intervals. Allocates nothing. A run that fails
    /// (the integrator gives up or diverges, the rover rolls over or
    /// leaves the map) stays where it failed, and so does every later
    /// step, until [`Stepper::reset`].
    pub fn step(&mut self, n: u64) -> Result<(), RunError> {
        if let Some(e) = &self.failed {
            return Err(e.clone());
        }
        for _ in 0..n {
            let stepped = self
                .driver
                .advance(&mut self.sys, &mut self.integ, &mut self.t, &mut self.y)
                .and_then(|()| self.refresh());
            if let Err(e) = stepped {
                self.failed = Some(e.clone());
                return Err(e);
            }
        }
        Ok(())
    }

    /// Advance to the time `until` \[s\] (a co-simulation master's next
    /// communication point), through every output instant before it: with
    /// `until` on an output instant, the steps of [`Stepper::step`], and so
    /// the whole run's rows there; between them, the integrator also lands
    /// on `until` (a fixed-step method shortens one step, an adaptive one
    /// chooses its steps anew). A time not after the current one does
    /// nothing. Allocates nothing; fails as [`Stepper::step`].
    pub fn advance_to(&mut self, until: f64) -> Result<(), RunError> {
        if let Some(e) = &self.failed {
            return Err(e.clone());
        }
        while until - self.t > SAME_INSTANT * (1.0 + self.t) {
            let stepped = self
                .driver
                .advance_until(
                    &mut self.sys,
                    &mut self.integ,
                    &mut self.t,
                    &mut self.y,
                    until,
                    &mut |_, _, _| Ok(()),
                )
                .and_then(|_| self.refresh());
            if let Err(e) = stepped {
                self.failed = Some(e.clone());
                return Err(e);
            }
        }
        Ok(())
    }

    /// The wheel states, contact reports and torques at (t, y), as the
    /// whole run evaluates them at an output instant.
    fn refresh(&mut self) -> Result<(), RunError> {
        self.sys.evaluate_at(self.t, &self.y, &mut self.scratch)
    }

    /// Time \[s\].
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The output interval, one step \[s\].
    pub fn dt(&self) -> f64 {
        self.driver.options().output_step
    }

    /// The row's columns, as the whole run's CSV names them.
    pub fn columns(&self) -> &Columns {
        &self.columns
    }

    /// The row at the current time into `out` (one value per column), the
    /// whole run's row at this output instant. Allocates nothing.
    pub fn row_into(&self, out: &mut [f64]) {
        let (sys, t) = (&self.sys, self.t);
        let inputs = RowInputs::of_system(sys, t, &self.y, sys.control.speed_setpoint(t));
        self.columns.fill(&inputs, out);
    }

    /// The full state `[x; w; ζ]`.
    pub fn state(&self) -> &[f64] {
        &self.y
    }

    /// Replace the full state `[x; w; ζ]` (as [`Stepper::state`] gives it)
    /// at the current time; the integrator restarts (a jump of the state)
    /// and the row is evaluated anew. Panics unless `y` has the state's length. A
    /// failed run stays failed until [`Stepper::reset`].
    pub fn set_state(&mut self, y: &[f64]) -> Result<(), RunError> {
        if let Some(e) = &self.failed {
            return Err(e.clone());
        }
        self.y.copy_from_slice(y);
        self.integ.restart();
        self.refresh()
            .inspect_err(|e| self.failed = Some(e.clone()))
    }

    /// The run's error, once it has failed.
    pub fn failure(&self) -> Option<&RunError> {
        self.failed.as_ref()
    }

    /// The system: wheel states, contact reports, torques and steering of
    /// the evaluation at the current time.
    pub fn system(&self) -> &RoverSystem<P, Terrain> {
        &self.sys
    }

    /// The scratch buffer for a command, one value per wheel: filled by
    /// the caller, then taken by [`Stepper::apply_torques`] or
    /// [`Stepper::apply_steering`] (so that a caller reading its values
    /// from elsewhere needs no buffer of its own).
    pub fn command_buffer(&mut self) -> &mut [f64] {
        &mut self.commands
    }

    /// The command buffer as open-loop torques [N·m]
    /// ([`RoverSystem::set_torques`]); the integrator restarts when they
    /// change (a jump of the right-hand side).
    pub fn apply_torques(&mut self) -> Result<(), CommandError> {
        if self.sys.commands().0 != self.commands.as_slice() {
            self.sys.set_torques(&self.commands)?;
            self.integ.restart();
        }
        Ok(())
    }

    /// The command buffer as open-loop steering angles \[rad\]
    /// ([`RoverSystem::set_steering`]), like [`Stepper::apply_torques`].
    pub fn apply_steering(&mut self) -> Result<(), CommandError> {
        if self.sys.commands().1 != self.commands.as_slice() {
            self.sys.set_steering(&self.commands)?;
            self.integ.restart();
        }
        Ok(())
    }

    /// Move spring `coord`'s neutral (an active suspension's set-point,
    /// 0-based over the suspension coordinates) to `neutral` \[rad or m\]
    /// ([`Controller::set_neutral`](rover_runtime::control::Controller::set_neutral));
    /// the integrator restarts when it changes.
    pub fn set_neutral(&mut self, coord: usize, neutral: f64) {
        if self.sys.control.neutrals().get(coord) != Some(&neutral) {
            let sys = &mut self.sys;
            sys.control.set_neutral(coord, neutral, &mut sys.plant);
            self.integ.restart();
        }
    }

    /// Hold the speed set-point at `speed` [m/s] ([`Controller::set_speed`](rover_runtime::control::Controller::set_speed)).
    pub fn set_speed(&mut self, speed: f64) -> Result<(), ControlError> {
        self.sys.control.set_speed(speed)?;
        self.integ.restart();
        Ok(())
    }

    /// Hold the steering set-point at `value`
    /// ([`Controller::set_steering_setpoint`](rover_runtime::control::Controller::set_steering_setpoint)).
    pub fn set_steering_setpoint(&mut self, value: f64) -> Result<(), ControlError> {
        self.sys.control.set_steering_setpoint(value)?;
        self.integ.restart();
        Ok(())
    }
}
