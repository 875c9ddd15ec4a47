//! `rover drive --estimate`: the rover as its own observer, live. At each
//! sensor instant the loop's driver lands on, the true state becomes the
//! readings of the rover's sensors (the scenario's `[sensors]`, or
//! [`default_sensors`]), and the model-based filter of `rover-estimate`
//! predicts over the interval with the commands the loop applied in it
//! and takes the readings. The page draws the estimate as a translucent
//! ghost beside the true rover (docs/DRIVE.md, "The estimate").
//!
//! Everything is sized in [`Ghost::new`]: a sensor instant allocates
//! nothing. A failure of the estimation (the filter's covariance losing
//! definiteness, its model's wheel off the map, …) never stops the
//! simulation: the ghost stops, says why ([`Ghost::error`]), and a reset
//! restarts it ([`Ghost::restart`]).

use std::path::Path;
use std::time::Instant;

use rover_dynamics::Model;
use rover_dynamics::plant::{Plant, WheelState};
use rover_estimate::{Estimator, SensorConfig, SensorSample, SensorSimulator, Truth};
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::Terrain;
use rover_scenario::estimate::{EstimateMap, Preset, process_system};
use rover_scenario::scenario::Scenario;
use rover_scenario::simulate::SetupError;

use super::live::Histogram;

/// The sensors `rover drive --estimate` gives a rover whose scenario
/// declares none: a MEMS set read at 100 Hz with seed 0 — an IMU at G,
/// its axes the body's (gyros 0.2 °/√h and 10 °/h, accelerometers
/// 100 µg/√Hz and 0.1 mg, biases wandering over 300 s), wheel encoders of
/// 1 mrad and suspension encoders of 0.1° (in a linear coordinate's
/// unit, 1.745 mm), without noise beyond their counts; no fix.
pub fn default_sensors() -> SensorConfig {
    SensorConfig::mems()
}

/// The names of the estimate's values in the state (docs/DRIVE.md): the
/// estimated pose and suspension coordinates, each wheel's centre at the
/// estimate, the 1σ of X, Y and ψ, and the estimate's time.
pub fn columns(m: usize, wheels: usize) -> Vec<String> {
    let mut names: Vec<String> = ["X", "Y", "Z", "phi", "theta", "psi"]
        .iter()
        .map(|c| format!("est_{c}"))
        .collect();
    names.extend((1..=m).map(|i| format!("est_y{i}")));
    for j in 1..=wheels {
        names.extend(["X", "Y", "Z"].map(|a| format!("est_W{j}{a}")));
    }
    names.extend(["est_sigma_X", "est_sigma_Y", "est_sigma_psi", "est_t"].map(String::from));
    names
}

/// Makes a filter as it starts: its process system as built, copied.
type Fresh<P> = Box<dyn Fn() -> Result<Estimator<RoverSystem<P, Terrain>>, SetupError> + Send>;

/// The filter of the rover's own model over the readings of its sensors,
/// fed the true state at each sensor instant (module docs).
pub struct Ghost<P: Plant> {
    filter: Estimator<RoverSystem<P, Terrain>>,
    /// A new filter as [`Ghost::new`] started it, for a restart.
    fresh: Fresh<P>,
    sensors: SensorSimulator,
    config: SensorConfig,
    sample: SensorSample,
    /// ẏ of the truth at the instant.
    dy: Vec<f64>,
    /// The wheels' true spin rates at the instant.
    rates: Vec<f64>,
    gravity: f64,
    n: usize,
    /// The commands the loop applies since `since`.
    torques: Vec<f64>,
    steering: Vec<f64>,
    since: f64,
    /// Their integrals over time since the last sample, then their means.
    torque_sum: Vec<f64>,
    steering_sum: Vec<f64>,
    /// The last sample's time, `None` before the first.
    last: Option<f64>,
    /// The springs' neutrals the filter's plant holds (an active
    /// suspension moves the true ones; the rover's computer knows them).
    neutrals: Vec<f64>,
    neutrals0: Vec<f64>,
    /// A copy of the plant for the wheel centres at the estimate.
    kinematics: P,
    wheels: Vec<WheelState>,
    sigma: Vec<f64>,
    /// Why the estimation stopped.
    error: Option<String>,
    /// The computing time of each sensor instant (readings, prediction,
    /// update).
    cost: Histogram,
}

impl<P: Plant + Clone + Send + 'static> Ghost<P> {
    /// The filter of `plant` (the loop's, its springs' neutrals at
    /// `neutrals`) on the scenario's ground, started from the scenario's
    /// initial state, over the readings of `sensors` on `model`; the
    /// loop's state is `state_len` long.
    pub fn new(
        plant: P,
        model: &Model,
        scenario: &Scenario,
        base: &Path,
        sensors: &SensorConfig,
        neutrals: &[f64],
        state_len: usize,
    ) -> Result<Self, SetupError> {
        let (wheels, m) = (model.wheels.len(), model.m());
        let simulator =
            SensorSimulator::new(sensors, wheels, m).map_err(|e| SetupError::Unsupported {
                field: e.field,
                message: e.message,
            })?;
        let mut kinematics = plant.clone();
        let (mut system0, y0) = process_system(plant, model, scenario, base, EstimateMap::True)?;
        for (i, &v) in neutrals.iter().enumerate() {
            kinematics.set_spring_neutral(i, v);
            system0.plant.set_spring_neutral(i, v);
        }
        let dim = y0.len();
        let config = sensors.clone();
        let fresh: Fresh<P> = Box::new(move || start(system0.clone(), &config, &y0));
        Ok(Ghost {
            filter: fresh()?,
            fresh,
            sample: simulator.new_sample(),
            sensors: simulator,
            config: sensors.clone(),
            dy: vec![0.0; state_len],
            rates: vec![0.0; wheels],
            gravity: model.gravity,
            n: model.dof(),
            torques: vec![0.0; wheels],
            steering: vec![0.0; wheels],
            since: 0.0,
            torque_sum: vec![0.0; wheels],
            steering_sum: vec![0.0; wheels],
            last: None,
            neutrals: neutrals.to_vec(),
            neutrals0: neutrals.to_vec(),
            kinematics,
            wheels: vec![WheelState::default(); wheels],
            sigma: vec![0.0; dim],
            error: None,
            cost: Histogram::default(),
        })
    }
}

impl<P: Plant> Ghost<P> {
    /// Back to before the first sample: the sensors' noise from its start,
    /// the filter anew from the initial state, the commands zero. Not a
    /// step: it may allocate.
    pub fn restart(&mut self) {
        self.sensors.reset();
        self.last = None;
        self.since = 0.0;
        for v in [
            &mut self.torques,
            &mut self.steering,
            &mut self.torque_sum,
            &mut self.steering_sum,
        ] {
            v.fill(0.0);
        }
        self.neutrals.copy_from_slice(&self.neutrals0);
        for (i, &v) in self.neutrals0.iter().enumerate() {
            self.kinematics.set_spring_neutral(i, v);
        }
        self.error = None;
        match (self.fresh)() {
            Ok(f) => self.filter = f,
            Err(e) => self.error = Some(format!("the estimator cannot restart: {e}")),
        }
    }

    /// The commands the loop applies from `t` on (at the start of each of
    /// its steps). Allocates nothing.
    pub fn hold(&mut self, t: f64, torques: &[f64], steering: &[f64]) {
        self.accumulate(t);
        self.torques.copy_from_slice(torques);
        self.steering.copy_from_slice(steering);
    }

    /// The commands held since `since` added to their integrals up to `t`.
    fn accumulate(&mut self, t: f64) {
        let dt = t - self.since;
        if dt > 0.0 {
            for (s, v) in self.torque_sum.iter_mut().zip(&self.torques) {
                *s += v * dt;
            }
            for (s, v) in self.steering_sum.iter_mut().zip(&self.steering) {
                *s += v * dt;
            }
        }
        self.since = t;
    }

    /// A sensor instant: the readings of the true state `(t, y)` of the
    /// loop's system `sys`, then a prediction over the interval since the
    /// last one with the mean commands applied in it, then the update.
    /// After a failure it does nothing until [`Ghost::restart`].
    /// Allocates nothing (but the failure's message).
    pub fn observe(&mut self, t: f64, y: &[f64], sys: &mut RoverSystem<P, Terrain>) {
        if self.error.is_some() {
            return;
        }
        let began = Instant::now();
        if let Err(why) = self.step(t, y, sys) {
            self.error = Some(format!("the estimator stopped at t = {t:.3} s: {why}"));
        }
        self.cost.record(began.elapsed().as_secs_f64());
    }

    fn step(&mut self, t: f64, y: &[f64], sys: &mut RoverSystem<P, Terrain>) -> Result<(), String> {
        sys.evaluate_at(t, y, &mut self.dy)
            .map_err(|e| e.to_string())?;
        sys.wheel_spin_rates(y, &mut self.rates);
        self.accumulate(t);
        let dt = self.last.map(|last| t - last);
        match dt {
            Some(dt) if dt > 0.0 => {
                self.torque_sum.iter_mut().for_each(|s| *s /= dt);
                self.steering_sum.iter_mut().for_each(|s| *s /= dt);
            }
            _ => {
                self.torque_sum.copy_from_slice(&self.torques);
                self.steering_sum.copy_from_slice(&self.steering);
            }
        }
        let n = self.n;
        let truth = Truth {
            t,
            x: &y[..n],
            w: &y[n..2 * n],
            w_dot: &self.dy[n..2 * n],
            wheel_rates: &self.rates,
            torques: &self.torque_sum,
            steering: &self.steering_sum,
            gravity: self.gravity,
        };
        let sampled = self.sensors.sample_into(&truth, &mut self.sample);
        let stepped = sampled.map_err(|e| e.to_string()).and_then(|()| {
            if let Some(dt) = dt {
                self.filter
                    .predict(dt, &self.torque_sum, &self.steering_sum)
                    .map_err(|e| e.to_string())?;
            }
            self.filter.update(&self.sample).map_err(|e| e.to_string())
        });
        self.torque_sum.fill(0.0);
        self.steering_sum.fill(0.0);
        self.last = Some(t);
        stepped?;
        // The neutrals an active suspension set for the coming interval.
        let plant = &mut self.filter.model_mut().plant;
        for (i, (held, &now)) in self
            .neutrals
            .iter_mut()
            .zip(sys.control.neutrals())
            .enumerate()
        {
            if *held != now {
                *held = now;
                plant.set_spring_neutral(i, now);
                self.kinematics.set_spring_neutral(i, now);
            }
        }
        Ok(())
    }

    /// The estimate's values into `out`, in the order of [`columns`]
    /// (`out` that long); NaN (`null` in JSON) once the estimation has
    /// stopped. Allocates nothing.
    pub fn fill(&mut self, out: &mut [f64]) {
        if self.error.is_some() {
            out.fill(f64::NAN);
            return;
        }
        let n = self.n;
        let y = self.filter.state();
        out[..n].copy_from_slice(&y[..n]);
        self.kinematics
            .wheels(&y[..n], &y[n..2 * n], &self.steering, &mut self.wheels);
        let mut at = n;
        for w in &self.wheels {
            out[at..at + 3].copy_from_slice(&w.centre);
            at += 3;
        }
        // Its own lengths: it cannot refuse them.
        let _ = self.filter.state_sigma(&mut self.sigma);
        out[at] = self.sigma[0];
        out[at + 1] = self.sigma[1];
        out[at + 2] = self.sigma[5];
        out[at + 3] = self.filter.time();
    }

    /// Why the estimation stopped, until a restart.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// The estimated model state `[x; w; ω]`.
    pub fn state(&self) -> &[f64] {
        self.filter.state()
    }

    /// The estimate's time \[s\]: the last sensor instant.
    pub fn time(&self) -> f64 {
        self.filter.time()
    }

    /// The sensors' declaration.
    pub fn sensors(&self) -> &SensorConfig {
        &self.config
    }

    /// The computing time of each sensor instant so far (the truth's
    /// evaluation, the readings, the prediction and the update).
    pub fn cost(&self) -> &Histogram {
        &self.cost
    }
}

/// A filter over `system` from `y0` at t = 0, with the preset tuning of
/// its ground (the map is the scenario's own).
fn start<P: Plant>(
    system: RoverSystem<P, Terrain>,
    sensors: &SensorConfig,
    y0: &[f64],
) -> Result<Estimator<RoverSystem<P, Terrain>>, SetupError> {
    let soil = !system.spin_range().is_empty();
    let (config, initial) = Preset::of(EstimateMap::True, soil).values();
    Estimator::new(system, sensors, config, 0.0, y0, &initial).map_err(|e| {
        SetupError::Unsupported {
            field: "--estimate",
            message: format!("the estimator cannot start: {e}"),
        }
    })
}
