//! The real-time loop: one fixed step per tick of the wall clock, the
//! operator's or rig's latest command applied at the start of each step,
//! the state published for the clients. It owns the whole simulation, so
//! the web side can only reach it through [`Shared`]: a command or a
//! reader never holds the loop up for longer than a copy.

use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use rover_dynamics::Model;
use rover_dynamics::plant::Plant;
use rover_estimate::SensorConfig;
use rover_integrate::{
    AnyIntegrator, FixedStepConfig, Integrator, IntegratorConfig, JacobianSource, OdeSystem,
    Ros2Config,
};
use rover_runtime::control::{
    Controller, ControllerConfig, DEFAULT_SLIP_BAND, DEFAULT_SLIP_THRESHOLD, Distribution,
    SpeedConfig, ackermann_angle, add_share, anti_spin_weight, curvature_from_angle,
    heading_centre_x,
};
use rover_runtime::row::{Columns, RowInputs};
use rover_runtime::sim::{CommandError, Driver, RoverSystem, RunError, RunOptions};
use rover_runtime::terrain::Terrain;
use rover_scenario::scenario::Scenario;
use rover_scenario::simulate::SetupError;
use rover_terrain::ruts::RutMap;

use super::ghost::Ghost;
use super::row_feed::RowFeed;
use super::rut_feed::{RUT_PERIOD, RutFeed};

/// The fixed-step method of the loop.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Method {
    /// Classical RK4: four right-hand sides a step, the cheapest step that
    /// is stable at 1 ms on every built-in rover's tyre stiffness.
    Rk4,
    /// Linearly implicit ROS2: a Jacobian and an LU a step, stable at 5 and
    /// 10 ms where an explicit method is not.
    Ros2,
    /// Semi-implicit Euler, order 1: the cheapest step, at short steps only.
    SemiImplicitEuler,
}

impl Method {
    /// The method for a loop rate: RK4 from 500 Hz up (a step of 2 ms or
    /// less, where it is stable and several times cheaper than ROS2),
    /// ROS2 below (the explicit methods diverge on the tyre modes at 5 ms).
    pub fn for_rate(rate_hz: f64) -> Method {
        if rate_hz >= 500.0 {
            Method::Rk4
        } else {
            Method::Ros2
        }
    }

    /// The integrator configuration at step `h`.
    pub fn config(self, h: f64) -> IntegratorConfig {
        match self {
            Method::Rk4 => IntegratorConfig::Rk4(FixedStepConfig { step: h }),
            Method::SemiImplicitEuler => {
                IntegratorConfig::SemiImplicitEuler(FixedStepConfig { step: h })
            }
            // The system's assembled Jacobian: the generated plant's exact
            // one and the wheels' load derivatives, one right-hand side
            // and a few plant-sized calls in place of `dim` differenced
            // right-hand sides (a generic plant has none: it differences).
            Method::Ros2 => IntegratorConfig::Ros2(Ros2Config {
                step: h,
                jacobian_every: 1,
                jacobian: JacobianSource::System,
            }),
        }
    }

    /// The name a scenario file gives the method.
    pub fn name(self) -> &'static str {
        match self {
            Method::Rk4 => "rk4",
            Method::Ros2 => "ros2",
            Method::SemiImplicitEuler => "semi_implicit_euler",
        }
    }
}

/// How the loop waits for the next tick.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, clap::ValueEnum)]
pub enum Pacing {
    /// Sleep until shortly before the tick (a margin that follows how late
    /// the sleeps wake), then spin on the clock: start lateness of a few
    /// µs, at the cost of the margin's CPU time each period.
    #[default]
    Spin,
    /// Sleep until the tick: no CPU time spent waiting, the scheduler's
    /// wake-up latency (tens of µs) as jitter.
    Sleep,
}

impl Pacing {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Pacing::Spin => "spin",
            Pacing::Sleep => "sleep",
        }
    }
}

/// How the motors are driven.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    /// The loop's speed controller turns `speed` into torques; `steer` or
    /// `delta_tau` steers.
    Speed,
    /// The client's own torques and steering angles, as given.
    Raw,
}

/// The command in force: what the clients last asked for. Held until
/// replaced (or until the watchdog zeroes it).
#[derive(Clone, Debug)]
pub struct Command {
    /// Which of the fields below drive the rover.
    pub mode: Mode,
    /// Speed set-point [m/s].
    pub speed: f64,
    /// Ackermann steering: the first steerable wheel's angle \[rad\].
    pub steer: f64,
    /// Slip steering: torque difference [N·m], taken from the left wheels
    /// and given to the right ones (positive turns left).
    pub delta_tau: f64,
    /// Raw motor torques per wheel [N·m].
    pub torques: Vec<f64>,
    /// Raw steering angles per wheel \[rad\].
    pub steering: Vec<f64>,
}

impl Command {
    /// Standing still: speed mode, every value zero.
    pub fn zero(wheels: usize) -> Self {
        Command {
            mode: Mode::Speed,
            speed: 0.0,
            steer: 0.0,
            delta_tau: 0.0,
            torques: vec![0.0; wheels],
            steering: vec![0.0; wheels],
        }
    }

    /// Copy `other` into `self` without allocating (same wheel count).
    fn assign(&mut self, other: &Command) {
        self.mode = other.mode;
        self.speed = other.speed;
        self.steer = other.steer;
        self.delta_tau = other.delta_tau;
        self.torques.copy_from_slice(&other.torques);
        self.steering.copy_from_slice(&other.steering);
    }

    fn stop(&mut self) {
        self.speed = 0.0;
        self.torques.iter_mut().for_each(|v| *v = 0.0);
    }
}

/// What the clients write and the loop reads at the start of each step.
#[derive(Debug)]
pub struct Inbox {
    /// Bumped at every change.
    pub seq: u64,
    /// The command.
    pub command: Command,
    /// Steps are skipped while true (the clock runs on).
    pub paused: bool,
    /// Bumped to ask for a reset to the initial state.
    pub resets: u64,
    /// Zero the speed and torques when no command came for this long \[s\];
    /// 0: never.
    pub watchdog_s: f64,
    /// When the last command came.
    pub last_command: Instant,
}

/// The state the loop publishes.
#[derive(Clone, Debug)]
pub struct Snapshot {
    /// Bumped at every publication.
    pub seq: u64,
    /// The row's values ([`Sim::columns`]), in the CSV's order.
    pub values: Vec<f64>,
    /// Wall-clock seconds since the loop started, when the state was computed.
    pub wall_s: f64,
    /// Simulated over wall-clock time over the last second, pauses excluded.
    pub real_time_factor: f64,
    /// Steps that ended after the next tick.
    pub overruns: u64,
    /// Ticks dropped to recover from overruns (simulated time lags by as many steps).
    pub dropped_ticks: u64,
    /// Steps taken.
    pub steps: u64,
    /// The last step's computing time \[s\].
    pub step_s: f64,
    /// Whether the loop is paused.
    pub paused: bool,
    /// Whether the watchdog has zeroed the command.
    pub watchdog_tripped: bool,
    /// Why the simulation stopped (it pauses; a reset restarts it).
    pub error: Option<String>,
    /// With `--estimate`, the estimate's values ([`super::ghost::columns`]);
    /// empty otherwise.
    pub estimate: Vec<f64>,
    /// Why the estimation stopped (the simulation goes on; a reset
    /// restarts it).
    pub estimate_error: Option<String>,
}

/// What the loop and the web side share.
#[derive(Debug)]
pub struct Shared {
    /// Commands in.
    pub inbox: Mutex<Inbox>,
    /// State out.
    pub state: Mutex<Snapshot>,
    /// Publish every this many steps (set from the clients' rates).
    pub publish_every: AtomicU64,
    /// Ends the loop.
    pub stop: AtomicBool,
    /// The ruts' tiles, copied by the loop every [`RUT_PERIOD`] when the
    /// ground keeps ruts.
    pub ruts: Mutex<RutFeed>,
    /// Every step's row, while [`Shared::row_readers`] is not 0.
    pub rows: Mutex<RowFeed>,
    /// Clients reading [`Shared::rows`] (the Foxglove sessions).
    pub row_readers: AtomicUsize,
}

/// The fastest speed set-point, in the rover's largest wheel radii a
/// second: the wheel turning at 50 rad/s (nearly 500 rpm), twenty-five
/// times the page's speed hint and far past any planetary rover's top
/// speed for its size (an LRV wheel of 0.41 m: 20 m/s).
pub const MAX_SPEED_RADII: f64 = 50.0;

/// The loop's rates \[Hz\] (steps per second): at 1 Hz a step is a
/// second, at 20 kHz 50 µs, near the cost of one RK4 step.
pub const RATE_RANGE: std::ops::RangeInclusive<f64> = 1.0..=20_000.0;

/// What the loop needs to know about the rover to turn a speed and
/// steering command into torques and angles.
#[derive(Clone, Debug)]
pub struct RoverInfo {
    /// Rest position (x, y, z) of each wheel centre from G, body axes \[m\].
    pub rest: Vec<[f64; 3]>,
    /// Which wheels steer.
    pub steerable: Vec<bool>,
    /// Whether each wheel is on the left (y > 0).
    pub left: Vec<bool>,
    /// Motor limits [N·m].
    pub max_torque: Vec<f64>,
    /// The largest motor limit [N·m]: where the speed loop's integral stops.
    pub torque_cap: f64,
    /// Wheel radii \[m\].
    pub radius: Vec<f64>,
    /// Turn centre's body x for Ackermann steering \[m\]: the mean x of the
    /// fixed wheels, or of all when all steer.
    pub centre_x: f64,
    /// Number of suspension coordinates.
    pub m: usize,
}

impl RoverInfo {
    /// From the model.
    pub fn new(model: &Model) -> Self {
        let rest = model.rest_wheel_centres();
        let steerable: Vec<bool> = model.wheels.iter().map(|w| w.steerable).collect();
        let rest_xy: Vec<(f64, f64)> = rest.iter().map(|p| (p[0], p[1])).collect();
        let centre_x = heading_centre_x(&rest_xy, &steerable);
        RoverInfo {
            left: rest.iter().map(|p| p[1] > 0.0).collect(),
            rest,
            steerable,
            max_torque: model.wheels.iter().map(|w| w.max_torque).collect(),
            torque_cap: model
                .wheels
                .iter()
                .map(|w| w.max_torque)
                .fold(0.0, f64::max),
            radius: model.wheels.iter().map(|w| w.radius).collect(),
            centre_x,
            m: model.m(),
        }
    }

    /// The largest |speed| set-point \[m/s\]: [`MAX_SPEED_RADII`] of the
    /// largest wheel's radii a second.
    pub fn max_speed(&self) -> f64 {
        MAX_SPEED_RADII * self.radius.iter().cloned().fold(0.0, f64::max)
    }

    /// The largest |delta_tau| \[N·m\]: twice the largest motor limit.
    /// Each wheel's torque is its share of the speed loop's plus or minus
    /// `delta_tau`, clamped to its motor limit: a larger difference only
    /// holds more of the wheels at their limits.
    pub fn max_delta_tau(&self) -> f64 {
        2.0 * self.torque_cap
    }

    /// Whether the rover steers with its wheels (Ackermann) rather than by
    /// slip.
    pub fn ackermann(&self) -> bool {
        self.steerable.iter().any(|s| *s)
    }
}

/// How the loop runs.
#[derive(Clone, Debug)]
pub struct LoopConfig {
    /// Steps per second of wall-clock time.
    pub rate_hz: f64,
    /// The method.
    pub method: Method,
    /// Speed loop gains: `kp` [N·m per m/s per wheel], `ki` [N·m per m per wheel].
    pub kp: f64,
    /// See `kp`.
    pub ki: f64,
    /// |φ| or |θ| beyond this stops the simulation \[rad\].
    pub rollover_limit: f64,
    /// How the speed loop's torque is shared among the wheels (the
    /// scenario's `[control.speed] distribution`).
    pub distribution: Distribution,
    /// The anti-spin distribution's slip threshold and band (the
    /// scenario's `slip_threshold`, `slip_band` or their defaults).
    pub anti_spin: (f64, f64),
    /// The scenario's controllers that run in the loop besides the speed
    /// loop: its active suspension.
    pub control: ControllerConfig,
    /// How the loop waits for a tick.
    pub pacing: Pacing,
}

impl LoopConfig {
    /// The loop at `rate_hz` with the scenario's speed gains (its
    /// `[control.speed]` `kp` and `ki`, or 10 and 10: a PI loop, so that the
    /// rover holds the set-point against rolling resistance and slopes).
    ///
    /// Of the scenario's other controllers, the active suspension runs in
    /// the loop as in a scenario run (sampled at its `sample_time`, moving
    /// the springs' neutrals); the speed profile, the steering (slip,
    /// Ackermann, heading hold) and the command file do not: the operator
    /// or rig gives the speed and steering live, and a second source of
    /// the same command would fight it.
    pub fn new(rate_hz: f64, method: Option<Method>, scenario: &Scenario) -> Self {
        let (kp, ki, distribution) = match &scenario.control.speed {
            Some(SpeedConfig {
                kp,
                ki,
                distribution,
                ..
            }) => (*kp, *ki, *distribution),
            None => (10.0, 10.0, Distribution::Even),
        };
        let speed = scenario.control.speed.as_ref();
        let anti_spin = (
            speed
                .and_then(|s| s.slip_threshold)
                .unwrap_or(DEFAULT_SLIP_THRESHOLD),
            speed.and_then(|s| s.slip_band).unwrap_or(DEFAULT_SLIP_BAND),
        );
        LoopConfig {
            rate_hz,
            method: method.unwrap_or(Method::for_rate(rate_hz)),
            kp,
            ki,
            rollover_limit: scenario.rollover_limit_deg.to_radians(),
            distribution,
            anti_spin,
            control: ControllerConfig {
                active_suspension: scenario.control.active_suspension.clone(),
                ..ControllerConfig::default()
            },
            pacing: Pacing::default(),
        }
    }
}

/// Latencies in 1 µs bins up to 100 ms (the last bin holds the rest):
/// recording allocates nothing, percentiles are exact to a microsecond.
#[derive(Clone, Debug)]
pub struct Histogram {
    bins: Vec<u32>,
    count: u64,
    max_s: f64,
}

impl Default for Histogram {
    fn default() -> Self {
        Histogram {
            bins: vec![0; 100_000],
            count: 0,
            max_s: 0.0,
        }
    }
}

impl Histogram {
    /// Count one latency \[s\].
    pub fn record(&mut self, s: f64) {
        let k = ((s * 1e6) as usize).min(self.bins.len() - 1);
        self.bins[k] = self.bins[k].saturating_add(1);
        self.count += 1;
        self.max_s = self.max_s.max(s);
    }

    /// The `q`-quantile (0…1) \[s\], to the bin's upper edge; 0 when empty.
    pub fn quantile(&self, q: f64) -> f64 {
        if self.count == 0 {
            return 0.0;
        }
        let target = ((q * self.count as f64).ceil() as u64).clamp(1, self.count);
        let mut seen = 0u64;
        for (k, &c) in self.bins.iter().enumerate() {
            seen += u64::from(c);
            if seen >= target {
                return (k + 1) as f64 * 1e-6;
            }
        }
        self.max_s
    }

    /// Largest value recorded \[s\].
    pub fn max(&self) -> f64 {
        self.max_s
    }

    /// Number of values recorded.
    pub fn count(&self) -> u64 {
        self.count
    }
}

/// Timing of a loop: computing time of the steps and lateness of their start.
#[derive(Clone, Debug, Default)]
pub struct Timing {
    /// Computing time of each step (commands, step, publication).
    pub compute: Histogram,
    /// How late each step started after its tick (the scheduler's jitter).
    pub late: Histogram,
    /// Steps that ended after the next tick.
    pub overruns: u64,
    /// Ticks dropped to recover.
    pub dropped_ticks: u64,
    /// Simulated time \[s\] and wall-clock time \[s\] over the whole run.
    pub simulated_s: f64,
    /// See `simulated_s`.
    pub wall_s: f64,
    /// Why the simulation stopped, if it did (it then waits for a reset).
    pub error: Option<RunError>,
    /// With [`Pacing::Spin`], how long before each tick the sleep ended at
    /// the end of the run (the spin's share of each period) \[s\].
    pub spin_margin_s: Option<f64>,
    /// With `--estimate`, the computing time of each sensor instant (the
    /// readings, the filter's prediction and update; part of the step
    /// that reaches it), and the sensors' rate \[Hz\].
    pub estimate: Option<(Histogram, f64)>,
    /// Why the estimation stopped, if it did.
    pub estimate_error: Option<String>,
}

/// The simulation the loop advances: the system, its integrator, the
/// state, and the speed controller the commands drive. Every buffer is
/// sized here: [`Sim::step`] allocates nothing.
pub struct Sim<P: Plant> {
    sys: RoverSystem<P, Terrain>,
    integ: AnyIntegrator,
    /// The run's events (the active suspension's samples), one step being
    /// one output interval.
    driver: Driver,
    columns: Columns,
    y: Vec<f64>,
    y0: Vec<f64>,
    scratch: Vec<f64>,
    t: f64,
    n: usize,
    info: RoverInfo,
    kp: f64,
    ki: f64,
    integral: f64,
    command: Command,
    torques: Vec<f64>,
    steering: Vec<f64>,
    distribution: Distribution,
    /// The anti-spin slip threshold and band.
    anti_spin: (f64, f64),
    /// The speed loop's weights per wheel: 1 (even), the static loads, or
    /// the loads (measured) or anti-spin weights of the slips of the last
    /// evaluation, refreshed each step.
    weights: Vec<f64>,
    /// The controller as built, for a reset (the active suspension's
    /// neutrals back at rest).
    control0: Controller,
    pacing: Pacing,
    /// With `--estimate`: the sensors and the filter.
    ghost: Option<Ghost<P>>,
}

impl<P: Plant> Sim<P> {
    /// The simulation of `plant` (whose model is `model`) on the
    /// scenario's ground, from its initial state.
    pub fn new(
        plant: P,
        model: &Model,
        scenario: &Scenario,
        base: &std::path::Path,
        config: &LoopConfig,
    ) -> Result<Self, SetupError> {
        // The step is a Duration the loop waits for.
        if !RATE_RANGE.contains(&config.rate_hz) {
            return Err(SetupError::Unsupported {
                field: "--rate",
                message: format!(
                    "{:?} steps per second: the loop runs from {} to {} Hz",
                    config.rate_hz,
                    RATE_RANGE.start(),
                    RATE_RANGE.end()
                ),
            });
        }
        let terrain = scenario.terrain.build(base)?;
        let mut y = rover_scenario::simulate::initial_state(model, scenario, Some(&terrain))?;
        let ground = rover_scenario::simulate::ground_of(scenario, terrain, model, base)?;
        rover_scenario::simulate::settle_into_soil(&ground, model, scenario, &mut y);
        let control = Controller::new_in(config.control.clone(), model, 0.0, base)?;
        let weights = match config.distribution {
            Distribution::StaticLoad => rover_runtime::quasi_static::flat_ground_loads(model)?,
            Distribution::Even | Distribution::MeasuredLoad | Distribution::AntiSpin => {
                vec![1.0; model.wheels.len()]
            }
        };
        let h = 1.0 / config.rate_hz;
        let driver = Driver::new(
            &control,
            RunOptions {
                duration: f64::INFINITY,
                output_step: h,
                rollover_limit: config.rollover_limit,
            },
        );
        let mut sys = RoverSystem::new(plant, Some(ground), control.clone());
        y.resize(sys.dim(), 0.0);
        sys.roll_spins(0.0, &mut y);
        let integ = config.method.config(h).build(sys.dim())?;
        let k = model.wheels.len();
        let mut sim = Sim {
            n: model.dof(),
            columns: Columns::on_ground(model.m(), k, !sys.spin_range().is_empty()),
            scratch: vec![0.0; y.len()],
            y0: y.clone(),
            y,
            sys,
            integ,
            driver,
            t: 0.0,
            info: RoverInfo::new(model),
            kp: config.kp,
            ki: config.ki,
            integral: 0.0,
            command: Command::zero(k),
            torques: vec![0.0; k],
            steering: vec![0.0; k],
            distribution: config.distribution,
            anti_spin: config.anti_spin,
            weights,
            control0: control,
            pacing: config.pacing,
            ghost: None,
        };
        sim.driver
            .start(&mut sim.sys, &mut sim.integ, sim.t, &sim.y);
        Ok(sim)
    }

    /// The step \[s\]: one output interval of the driver.
    fn h(&self) -> f64 {
        self.driver.options().output_step
    }

    /// The row's columns, as the CSV of a run names them.
    pub fn columns(&self) -> &Columns {
        &self.columns
    }

    /// The springs' neutrals y0 in force (moved by an active suspension).
    pub fn neutrals(&self) -> &[f64] {
        self.sys.control.neutrals()
    }

    /// Simulated time \[s\].
    pub fn t(&self) -> f64 {
        self.t
    }

    /// The state `[x; w; ζ]`.
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// The ruts the wheels left, when the ground keeps them.
    pub fn ruts(&self) -> Option<&RutMap> {
        Some(self.sys.ground.as_ref()?.ruts()?.map())
    }

    /// The rover's geometry as the loop uses it.
    pub fn info(&self) -> &RoverInfo {
        &self.info
    }

    /// Replace the command in force (no allocation).
    pub fn set_command(&mut self, c: &Command) {
        self.command.assign(c);
    }

    /// Back to the initial state at t = 0, commands zeroed.
    pub fn reset(&mut self) {
        self.y.copy_from_slice(&self.y0);
        self.t = 0.0;
        // The neutrals back where they started (a reset is not a step:
        // the copy may allocate).
        self.sys.control = self.control0.clone();
        for (i, &n) in self.control0.neutrals().iter().enumerate() {
            self.sys.plant.set_spring_neutral(i, n);
        }
        self.integral = 0.0;
        self.integ.restart();
        self.driver.rewind();
        match &mut self.ghost {
            Some(ghost) => {
                ghost.restart();
                // The ghost's errors are its own: the callback never fails.
                let _ = self.driver.start_with(
                    &mut self.sys,
                    &mut self.integ,
                    self.t,
                    &self.y,
                    &mut |t, y, sys| {
                        ghost.observe(t, y, sys);
                        Ok(())
                    },
                );
            }
            None => self
                .driver
                .start(&mut self.sys, &mut self.integ, self.t, &self.y),
        }
        self.command.stop();
        self.command.steer = 0.0;
        self.command.delta_tau = 0.0;
        self.command.steering.iter_mut().for_each(|v| *v = 0.0);
    }

    /// The speed set-point in force [m/s] (0 in raw mode).
    pub fn speed_setpoint(&self) -> f64 {
        match self.command.mode {
            Mode::Speed => self.command.speed,
            Mode::Raw => 0.0,
        }
    }

    /// The torques and angles of the command in force, from the state at
    /// the start of the step: the speed loop is sampled at the loop's rate
    /// (its time constant, tens of ms, is many steps).
    fn actuate(&mut self) {
        let info = &self.info;
        match self.command.mode {
            Mode::Raw => {
                self.torques.copy_from_slice(&self.command.torques);
                for (k, s) in self.steering.iter_mut().enumerate() {
                    *s = if info.steerable[k] {
                        self.command.steering[k]
                    } else {
                        0.0
                    };
                }
            }
            Mode::Speed => {
                let vx = self.y[self.n];
                let e = self.command.speed - vx;
                let cap = info.torque_cap;
                // Anti-windup: the integral stops growing while its term
                // alone saturates the motors in the same direction.
                let held = self.ki * self.integral;
                if !((held >= cap && e > 0.0) || (held <= -cap && e < 0.0)) {
                    self.integral += e * self.h();
                }
                let tau0 = self.kp * e + self.ki * self.integral;
                let dt = if info.ackermann() {
                    0.0
                } else {
                    self.command.delta_tau
                };
                if self.distribution == Distribution::MeasuredLoad {
                    for (w, r) in self.weights.iter_mut().zip(self.sys.reports()) {
                        *w = r.normal.max(0.0);
                    }
                }
                if self.distribution == Distribution::AntiSpin {
                    let (threshold, band) = self.anti_spin;
                    for (w, r) in self.weights.iter_mut().zip(self.sys.reports()) {
                        // A wheel in the air spins.
                        let slip = if r.patches == 0 { 1.0 } else { r.slip };
                        *w = anti_spin_weight(slip, threshold, band);
                    }
                }
                // τ0 per wheel on the mean, shared by the weights.
                self.torques.iter_mut().for_each(|t| *t = 0.0);
                add_share(tau0, &self.weights, &mut self.torques);
                for (k, t) in self.torques.iter_mut().enumerate() {
                    let side = if info.left[k] { -dt } else { dt };
                    *t = (*t + side).clamp(-info.max_torque[k], info.max_torque[k]);
                }
                let first = info.steerable.iter().position(|s| *s);
                let kappa = match first {
                    Some(j) if self.command.steer != 0.0 => curvature_from_angle(
                        self.command.steer,
                        info.rest[j][0],
                        info.rest[j][1],
                        info.centre_x,
                    ),
                    _ => 0.0,
                };
                for (k, s) in self.steering.iter_mut().enumerate() {
                    *s = if info.steerable[k] {
                        let [x, y, _] = info.rest[k];
                        ackermann_angle(kappa, x, y, info.centre_x)
                    } else {
                        0.0
                    };
                }
            }
        }
    }

    /// One step of `h`: the command applied, then the run's driver (the
    /// active suspension's samples, the checks of a diverged integration
    /// and a roll-over). On failure (the integrator's error, a wheel off
    /// the terrain map, a divergence, a roll-over) the state is that of
    /// the last good step.
    pub fn step(&mut self) -> Result<(), RunError> {
        self.actuate();
        // Torques and steering were checked (finite, one per wheel, only
        // steerable wheels steer) when the command came in: the system
        // takes them as they are.
        let t = self.t;
        let command = |e: CommandError| RunError::Integration {
            t,
            message: e.to_string(),
            step_control: false,
        };
        self.sys.set_torques(&self.torques).map_err(command)?;
        self.sys.set_steering(&self.steering).map_err(command)?;
        match &mut self.ghost {
            Some(ghost) => {
                ghost.hold(self.t, &self.torques, &self.steering);
                self.driver.advance_with(
                    &mut self.sys,
                    &mut self.integ,
                    &mut self.t,
                    &mut self.y,
                    &mut |t, y, sys| {
                        ghost.observe(t, y, sys);
                        Ok(())
                    },
                )
            }
            None => self
                .driver
                .advance(&mut self.sys, &mut self.integ, &mut self.t, &mut self.y),
        }
    }

    /// The row at the current state into `out`, the CSV's columns (one
    /// right-hand side evaluates the contact reports there).
    pub fn row(&mut self, out: &mut [f64]) {
        // An evaluation error leaves the last evaluation's reports: the
        // step that follows reports the error itself.
        let _ = self.sys.evaluate_at(self.t, &self.y, &mut self.scratch);
        let inputs = RowInputs::of_system(&self.sys, self.t, &self.y, self.speed_setpoint());
        self.columns.fill(&inputs, out);
    }

    /// The estimator, with `--estimate`.
    pub fn ghost(&self) -> Option<&Ghost<P>> {
        self.ghost.as_ref()
    }

    /// The number of the estimate's values ([`super::ghost::columns`]): 0
    /// without `--estimate`.
    pub fn estimate_len(&self) -> usize {
        match &self.ghost {
            Some(_) => super::ghost::columns(self.info.m, self.info.rest.len()).len(),
            None => 0,
        }
    }

    /// The estimate's values into `out` ([`Sim::estimate_len`] long): NaN
    /// once the estimation has stopped; nothing without `--estimate`.
    pub fn estimate_row(&mut self, out: &mut [f64]) {
        if let Some(g) = &mut self.ghost {
            g.fill(out);
        }
    }

    /// Why the estimation stopped, until a reset.
    pub fn estimate_error(&self) -> Option<&str> {
        self.ghost.as_ref().and_then(Ghost::error)
    }

    /// The state shared with the web side, sized for this simulation (its
    /// row and, with `--estimate`, the estimate), publishing at `rate_hz`
    /// / 30 steps until a client asks for more.
    pub fn shared(&self, rate_hz: f64) -> Arc<Shared> {
        let shared = shared(self.columns.len(), self.info.rest.len(), rate_hz);
        if let Ok(mut s) = shared.state.lock() {
            s.estimate = vec![0.0; self.estimate_len()];
        }
        shared
    }
}

impl<P: Plant + Clone + Send + 'static> Sim<P> {
    /// The simulation with the rover's own observer (`--estimate`): the
    /// readings of `sensors` at their instants (the driver lands on them)
    /// feed the model-based filter, started from the initial state.
    pub fn with_estimate(
        mut self,
        model: &Model,
        scenario: &Scenario,
        base: &std::path::Path,
        sensors: &SensorConfig,
    ) -> Result<Self, SetupError> {
        let ghost = Ghost::new(
            self.sys.plant.clone(),
            model,
            scenario,
            base,
            sensors,
            self.control0.neutrals(),
            self.y.len(),
        )?;
        self.ghost = Some(ghost);
        self.driver = self
            .driver
            .clone()
            .with_sensor_period(Some(1.0 / sensors.rate));
        // From t = 0 again, the first readings taken there.
        self.reset();
        Ok(self)
    }
}

/// Waits for the ticks: [`Pacing::Sleep`] sleeps to the tick;
/// [`Pacing::Spin`] sleeps to `margin` before it and spins the rest. The
/// margin tracks the 99th percentile of how late the sleeps wake (a
/// stochastic quantile estimate: up 99 units when a sleep wakes later
/// than the margin, down one unit otherwise, a unit being 0.2 µs), between
/// 10 µs and a tenth of the period. A wake-up delayed by a preemption
/// (later than that bound) is no timer latency and leaves the margin
/// alone: no margin would catch it, and spinning longer only costs CPU.
struct Waiter {
    pacing: Pacing,
    margin: f64,
    min: f64,
    max: f64,
}

/// The quantile estimate's unit \[s\].
const MARGIN_UNIT: f64 = 0.2e-6;

impl Waiter {
    fn new(pacing: Pacing, period: Duration) -> Self {
        let min = 10e-6;
        let max = (0.1 * period.as_secs_f64()).max(min);
        if pacing == Pacing::Spin {
            timer_slack_1ns();
        }
        Waiter {
            pacing,
            margin: (50e-6f64).clamp(min, max),
            min,
            max,
        }
    }

    fn wait_until(&mut self, deadline: Instant) {
        let now = Instant::now();
        if deadline <= now {
            return;
        }
        match self.pacing {
            Pacing::Sleep => std::thread::sleep(deadline - now),
            Pacing::Spin => {
                let margin = Duration::from_secs_f64(self.margin);
                if let Some(nap) = (deadline - now).checked_sub(margin) {
                    let target = now + nap;
                    std::thread::sleep(nap);
                    let late = Instant::now()
                        .saturating_duration_since(target)
                        .as_secs_f64();
                    if late > self.margin && late <= self.max {
                        self.margin = (self.margin + 99.0 * MARGIN_UNIT).min(self.max);
                    } else if late <= self.margin {
                        self.margin = (self.margin - MARGIN_UNIT).max(self.min);
                    }
                }
                while Instant::now() < deadline {
                    std::hint::spin_loop();
                }
            }
        }
    }
}

/// Linux: this thread's timer slack to 1 ns (from the default 50 µs), so
/// that a sleep wakes when asked rather than up to 50 µs later.
#[cfg(target_os = "linux")]
fn timer_slack_1ns() {
    const PR_SET_TIMERSLACK: std::ffi::c_int = 29;
    unsafe extern "C" {
        fn prctl(option: std::ffi::c_int, ...) -> std::ffi::c_int;
    }
    // SAFETY: PR_SET_TIMERSLACK takes one unsigned long and changes only
    // the calling thread's timer slack; a failure leaves it as it was.
    unsafe {
        prctl(PR_SET_TIMERSLACK, 1 as std::ffi::c_ulong);
    }
}

#[cfg(not(target_os = "linux"))]
fn timer_slack_1ns() {}

/// Run the loop until `shared.stop` is set (or, with `max_wall_s`, for
/// that long), publishing into `shared`. Each tick: read the inbox
/// (without waiting: a client holding the lock delays the command by one
/// step, never the step), take one step, publish every
/// `publish_every` steps.
///
/// A step that ends after the next tick is an overrun: the ticks it ran
/// into are dropped, not caught up, so a slow step never causes a burst
/// of steps that would overrun in turn; simulated time then lags the
/// wall clock by the dropped steps, which the real-time factor shows.
pub fn run<P: Plant>(sim: &mut Sim<P>, shared: &Shared, max_wall_s: Option<f64>) -> Timing {
    // `Sim::new` took a rate within RATE_RANGE: the step is a Duration.
    let period = Duration::from_secs_f64(sim.h());
    let columns = shared.state.lock().map(|s| s.values.len()).unwrap_or(0);
    let mut row = vec![0.0; columns];
    let mut estimate = vec![0.0; sim.estimate_len()];
    let mut command = Command::zero(sim.info.rest.len());
    let mut seen_seq = u64::MAX;
    let mut seen_resets = 0u64;
    let mut paused = false;
    let mut tripped = false;
    let mut error: Option<RunError> = None;
    let mut timing = Timing::default();
    let mut steps = 0u64;
    let mut last_step_s = 0.0;
    // The real-time factor over windows of about a second.
    let mut rtf = 0.0;
    let (mut window_sim, mut window_wall) = (0.0, 0.0);
    let start = Instant::now();
    let mut tick: u64 = 0;
    let mut published_at = 0u64;
    let mut waiter = Waiter::new(sim.pacing, period);
    let mut ruts_copied = start;
    while !shared.stop.load(Ordering::Relaxed) {
        let deadline = start + period.mul_f64(tick as f64);
        if let Some(limit) = max_wall_s
            && (deadline - start).as_secs_f64() >= limit
        {
            break;
        }
        waiter.wait_until(deadline);
        let woke = Instant::now();
        timing.late.record((woke - deadline).as_secs_f64());
        if let Ok(mut inbox) = shared.inbox.try_lock() {
            let expired = inbox.watchdog_s > 0.0
                && inbox.last_command.elapsed().as_secs_f64() > inbox.watchdog_s;
            if expired && !tripped {
                // Zeroed in the inbox itself: a later message that is not
                // a command (a rate, a pause) does not bring it back.
                inbox.command.stop();
                inbox.seq += 1;
            }
            tripped = expired;
            if inbox.seq != seen_seq {
                seen_seq = inbox.seq;
                command.assign(&inbox.command);
                paused = inbox.paused;
                sim.set_command(&command);
            }
            if inbox.resets != seen_resets {
                seen_resets = inbox.resets;
                sim.reset();
                command.stop();
                error = None;
                if let Ok(mut feed) = shared.rows.lock() {
                    feed.clear();
                }
            }
        }
        let stepping = !paused && error.is_none();
        if stepping {
            if let Err(e) = sim.step() {
                error = Some(e);
            }
            steps += 1;
            window_sim += sim.h();
        }
        // Every step's row for the clients that take them all; the row
        // is computed once for them and the state below.
        let mut row_now = false;
        if stepping && shared.row_readers.load(Ordering::Relaxed) > 0 {
            sim.row(&mut row);
            row_now = true;
            if let Ok(mut feed) = shared.rows.try_lock() {
                feed.push(&row);
            }
        }
        let publish_every = shared.publish_every.load(Ordering::Relaxed).max(1);
        if tick >= published_at + publish_every
            && let Ok(mut s) = shared.state.try_lock()
        {
            published_at = tick;
            if !row_now {
                sim.row(&mut row);
            }
            s.values.copy_from_slice(&row);
            if !estimate.is_empty() && s.estimate.len() == estimate.len() {
                sim.estimate_row(&mut estimate);
                s.estimate.copy_from_slice(&estimate);
            }
            match sim.estimate_error() {
                // Once per failure: a message for the clients.
                Some(e) if s.estimate_error.is_none() => s.estimate_error = Some(e.to_string()),
                Some(_) => {}
                None => s.estimate_error = None,
            }
            s.seq += 1;
            s.wall_s = (woke - start).as_secs_f64();
            s.real_time_factor = rtf;
            s.overruns = timing.overruns;
            s.dropped_ticks = timing.dropped_ticks;
            s.steps = steps;
            s.step_s = last_step_s;
            s.paused = paused;
            s.watchdog_tripped = tripped;
            if s.error.is_none() && error.is_some() {
                // Once per failure: a message for the clients.
                s.error = error.as_ref().map(RunError::to_string);
            } else if error.is_none() {
                s.error = None;
            }
        }
        if let Some(map) = sim.ruts()
            && woke - ruts_copied >= RUT_PERIOD
            && let Ok(mut feed) = shared.ruts.try_lock()
        {
            ruts_copied = woke;
            feed.update(map);
        }
        let done = Instant::now();
        last_step_s = (done - woke).as_secs_f64();
        if stepping {
            timing.compute.record(last_step_s);
            window_wall += period.as_secs_f64();
        }
        tick += 1;
        let next = start + period.mul_f64(tick as f64);
        if done > next {
            timing.overruns += 1;
            let behind = (done - next).as_secs_f64() / period.as_secs_f64();
            let missed = behind.ceil() as u64;
            timing.dropped_ticks += missed;
            tick += missed;
            if stepping {
                window_wall += missed as f64 * period.as_secs_f64();
            }
        }
        if window_wall >= 1.0 {
            rtf = window_sim / window_wall;
            window_sim = 0.0;
            window_wall = 0.0;
        }
    }
    timing.simulated_s = sim.t();
    timing.wall_s = start.elapsed().as_secs_f64();
    timing.error = error;
    timing.spin_margin_s = (waiter.pacing == Pacing::Spin).then_some(waiter.margin);
    if let Some(g) = sim.ghost() {
        timing.estimate = Some((g.cost().clone(), g.sensors().rate));
        timing.estimate_error = g.error().map(str::to_string);
    }
    timing
}

/// The shared state for a rover with `columns` CSV columns and `wheels` wheels.
pub fn shared(columns: usize, wheels: usize, rate_hz: f64) -> Arc<Shared> {
    Arc::new(Shared {
        inbox: Mutex::new(Inbox {
            seq: 0,
            command: Command::zero(wheels),
            paused: false,
            resets: 0,
            watchdog_s: 0.0,
            last_command: Instant::now(),
        }),
        state: Mutex::new(Snapshot {
            seq: 0,
            values: vec![0.0; columns],
            wall_s: 0.0,
            real_time_factor: 0.0,
            overruns: 0,
            dropped_ticks: 0,
            steps: 0,
            step_s: 0.0,
            paused: false,
            watchdog_tripped: false,
            error: None,
            estimate: Vec::new(),
            estimate_error: None,
        }),
        // 30 Hz until a client asks for more.
        publish_every: AtomicU64::new(((rate_hz / 30.0).floor() as u64).max(1)),
        stop: AtomicBool::new(false),
        ruts: Mutex::new(RutFeed::default()),
        rows: Mutex::new(RowFeed::new(columns)),
        row_readers: AtomicUsize::new(0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::drive::{ghost, protocol};

    /// A failure of the estimation stops the estimate, not the loop: a
    /// reading out of time order (the sensors refuse it) ends the
    /// estimation with a message naming the time; the simulation steps on,
    /// the state carries `null` estimates, the message once in
    /// `est_error` and the binary frame's flag; a reset restarts the
    /// filter from the initial state.
    #[test]
    fn an_estimator_failure_stops_the_estimate_not_the_simulation() {
        let spec =
            rover_spec::load_str(rover_models::builtin("swing4").unwrap(), "swing4").unwrap();
        let scenario = Scenario::parse("duration = 1.0\n", std::path::Path::new("s.toml")).unwrap();
        let dir = std::path::Path::new(".");
        let model = &spec.model;
        let config = LoopConfig::new(1000.0, None, &scenario);
        let mut sim = Sim::new(rover_models::Swing4::new(), model, &scenario, dir, &config)
            .unwrap()
            .with_estimate(model, &scenario, dir, &ghost::default_sensors())
            .unwrap();
        let mut command = Command::zero(4);
        command.speed = 0.1;
        sim.set_command(&command);
        for _ in 0..100 {
            sim.step().unwrap();
        }
        assert_eq!(sim.estimate_error(), None);
        let ghost = sim.ghost.as_mut().unwrap();
        ghost.observe(sim.t - 0.05, &sim.y, &mut sim.sys);
        let why = sim.estimate_error().unwrap().to_string();
        assert!(
            why.starts_with("the estimator stopped at t = 0.050 s: a sensor sample at t = 0.05")
                && why.contains("does not follow"),
            "{why}"
        );
        for _ in 0..100 {
            sim.step().unwrap();
        }
        assert!((sim.t() - 0.2).abs() < 1e-9);
        assert_eq!(sim.estimate_error(), Some(why.as_str()));
        let mut est = vec![0.0; sim.estimate_len()];
        sim.estimate_row(&mut est);
        assert!(est.iter().all(|v| v.is_nan()), "{est:?}");
        // Published: null values, the message, the flag.
        let shared = sim.shared(1000.0);
        shared.publish_every.store(1, Ordering::Relaxed);
        let timing = run(&mut sim, &shared, Some(0.05));
        assert!(timing.error.is_none() && sim.t() > 0.2);
        assert_eq!(timing.estimate_error.as_deref(), Some(why.as_str()));
        let names = ghost::columns(model.m(), 4);
        let columns = sim.columns().names().to_vec();
        let s = shared.state.lock().unwrap();
        let json: serde_json::Value =
            serde_json::from_str(&protocol::state_json(&columns, &names, &s)).unwrap();
        assert!(
            json["est_X"].is_null() && json["est_W4Z"].is_null(),
            "{json}"
        );
        assert_eq!(json["est_error"], why.as_str());
        assert!(json["error"].is_null());
        let frame = protocol::state_binary(&s);
        let flags = f64::from_le_bytes(frame[56..64].try_into().unwrap());
        assert_eq!(flags as u32, protocol::FLAG_ESTIMATE_ERROR);
        drop(s);
        // A reset: the filter anew at t = 0, from the initial state.
        sim.reset();
        assert_eq!(sim.estimate_error(), None);
        sim.estimate_row(&mut est);
        assert!(est.iter().all(|v| v.is_finite()), "{est:?}");
        assert_eq!(est[names.len() - 1], 0.0);
        for i in 0..3 {
            assert!((est[i] - sim.y()[i]).abs() < 1e-3, "{est:?}");
        }
    }
}
