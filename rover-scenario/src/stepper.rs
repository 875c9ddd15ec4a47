//! A run advanced by the caller, one output interval at a time: what a
//! step-wise caller (the Python package's `Simulation`, a learning agent's
//! environment) drives. Between steps it may read the state and change the
//! open-loop commands and the set-points. A step takes the same events, in
//! the same order, as [`rover_runtime::sim::run`], so that a run stepped without
//! changes gives the rows of the whole run bit for bit.

use std::path::Path;

use rover_dynamics::Model;
use rover_dynamics::plant::Plant;

use crate::scenario::{FidelityLevel, Scenario};
use crate::simulate::{SetupError, system_of};
use rover_integrate::{AnyIntegrator, Integrator, OdeSystem};
use rover_runtime::control::ControlError;
use rover_terrain::Terrain;

use rover_runtime::sim::{CommandError, RoverSystem, RunError};

/// A run under the caller's control (see the module's documentation).
#[derive(Clone, Debug)]
pub struct Stepper<P> {
    start: RoverSystem<P, Terrain>,
    sys: RoverSystem<P, Terrain>,
    integ_start: AnyIntegrator,
    integ: AnyIntegrator,
    y0: Vec<f64>,
    y: Vec<f64>,
    scratch: Vec<f64>,
    commands: Vec<f64>,
    t: f64,
    steps: u64,
    dt: f64,
    sample: Option<f64>,
    k_sample: u64,
    breaks: Vec<f64>,
    next_break: usize,
    rollover: f64,
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
        let mut breaks: Vec<f64> = sys
            .control
            .breakpoints()
            .into_iter()
            .filter(|&b| b > 0.0)
            .collect();
        breaks.sort_by(f64::total_cmp);
        let mut s = Self {
            sample: sys.control.sample_period(),
            start: sys.clone(),
            integ_start: integ.clone(),
            scratch: vec![0.0; y.len()],
            commands: vec![0.0; sys.plant.wheel_count()],
            sys,
            integ,
            y0: y.clone(),
            y,
            t: 0.0,
            steps: 0,
            dt: 1.0 / scenario.output_rate,
            k_sample: 0,
            breaks,
            next_break: 0,
            rollover: scenario.rollover_limit_deg.to_radians(),
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
        self.steps = 0;
        self.k_sample = 0;
        self.next_break = 0;
        self.failed = None;
        self.events();
        self.refresh();
    }

    /// Advance `n` output intervals. Allocates nothing. A run that fails
    /// (the integrator gives up, the rover rolls over or leaves the map)
    /// stays where it failed, and so does every later step, until
    /// [`Stepper::reset`].
    pub fn step(&mut self, n: u64) -> Result<(), RunError> {
        if let Some(e) = &self.failed {
            return Err(e.clone());
        }
        for _ in 0..n {
            if let Err(e) = self.one() {
                self.failed = Some(e.clone());
                return Err(e);
            }
        }
        Ok(())
    }

    /// Controller samples due at the current time.
    fn events(&mut self) {
        let n = self.sys.dof();
        if let Some(dt) = self.sample
            && (self.k_sample as f64 * dt - self.t).abs() <= 1e-12 * (1.0 + self.t)
        {
            let (x, rest) = self.y.split_at(n);
            if self
                .sys
                .control
                .sample(self.t, x, &rest[..n], &mut self.sys.plant)
            {
                self.integ.restart();
            }
            self.k_sample += 1;
        }
    }

    /// The wheel states, contact reports and torques at (t, y), as the
    /// run driver evaluates them at an output instant.
    fn refresh(&mut self) -> Option<RunError> {
        let t = self.t;
        self.sys
            .rhs(t, &self.y, &mut self.scratch)
            .err()
            .map(|e| RunError::Integration {
                t,
                message: e.to_string(),
                step_control: false,
            })
    }

    /// One output interval, through every controller sample and command
    /// breakpoint in it (the run driver's loop between two outputs).
    fn one(&mut self) -> Result<(), RunError> {
        let end = (self.steps + 1) as f64 * self.dt;
        loop {
            while self.next_break < self.breaks.len() && self.breaks[self.next_break] <= self.t {
                self.next_break += 1;
            }
            let mut target = end;
            if let Some(dt) = self.sample {
                target = target.min(self.k_sample as f64 * dt);
            }
            let at_break = self.next_break < self.breaks.len()
                && self.breaks[self.next_break] <= target + 1e-12 * (1.0 + target);
            if at_break {
                target = self.breaks[self.next_break];
            }
            self.sys.set_next_break(at_break.then_some(target));
            let advanced = self
                .integ
                .advance(&mut self.sys, &mut self.t, &mut self.y, target);
            self.sys.set_next_break(None);
            if let Err(e) = advanced {
                let te = e.time().unwrap_or(self.t);
                return Err(RunError::Integration {
                    t: te,
                    message: e.to_string(),
                    step_control: e.is_step_control(),
                });
            }
            if at_break {
                self.integ.restart();
            }
            let (roll, pitch) = (self.y[3], self.y[4]);
            if roll.abs() > self.rollover || pitch.abs() > self.rollover {
                return Err(RunError::RolledOver {
                    t: self.t,
                    roll_deg: roll.to_degrees(),
                    pitch_deg: pitch.to_degrees(),
                    limit_deg: self.rollover.to_degrees(),
                });
            }
            self.events();
            if (end - self.t).abs() <= 1e-12 * (1.0 + self.t) {
                self.steps += 1;
                return self.refresh().map_or(Ok(()), Err);
            }
        }
    }

    /// Time \[s\].
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The output interval, one step \[s\].
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The full state `[x; w; ζ]`.
    pub fn state(&self) -> &[f64] {
        &self.y
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

    /// Hold the speed set-point at `speed` [m/s] ([`Controller::set_speed`]).
    pub fn set_speed(&mut self, speed: f64) -> Result<(), ControlError> {
        self.sys.control.set_speed(speed)?;
        self.integ.restart();
        Ok(())
    }

    /// Hold the steering set-point at `value`
    /// ([`Controller::set_steering_setpoint`]).
    pub fn set_steering_setpoint(&mut self, value: f64) -> Result<(), ControlError> {
        self.sys.control.set_steering_setpoint(value)?;
        self.integ.restart();
        Ok(())
    }
}
