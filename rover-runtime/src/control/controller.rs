//! The controller of a run: speed loop, torque distribution, steering and
//! active suspension together, driven by time profiles.

use rover_dynamics::Model;
use rover_dynamics::model::MotorCurve;
use rover_dynamics::plant::Plant;
use serde::{Deserialize, Serialize};

use crate::quasi_static::flat_ground_loads;

use super::active_suspension::{ActiveSuspension, ActiveSuspensionConfig, SuspensionLaw};
use super::commands::{CommandSchedule, CommandsConfig};
use super::distribution::{DEFAULT_SLIP_BAND, DEFAULT_SLIP_THRESHOLD, Distribution};
use super::law::{CurvatureCommand, SpeedLaw, SteeringLaw};
use super::profile::Profile;
use super::speed::SpeedConfig;
use super::steering::{
    HeadingActuator, HeadingHold, HeadingIntegrals, LINE_INTEGRAL_CAP, Steering, ackermann_angle,
};

/// The `[control]` table of a scenario.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ControllerConfig {
    /// The speed loop; absent: the motors give no torque.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed: Option<SpeedConfig>,
    /// Steering.
    #[serde(default)]
    pub steering: Steering,
    /// Active suspension; absent: passive.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub active_suspension: Option<ActiveSuspensionConfig>,
    /// Open-loop torques and steering angles from a CSV file, added to the
    /// loops' commands; absent: none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub commands: Option<CommandsConfig>,
}

/// A controller that cannot run on this rover.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("control.{field}: {message}")]
pub struct ControlError {
    /// Dotted path of the offending field.
    pub field: String,
    /// What is wrong and how to fix it.
    pub message: String,
}

fn err(field: &str, message: impl std::fmt::Display) -> ControlError {
    ControlError {
        field: field.into(),
        message: message.to_string(),
    }
}

/// The running controller: the `[control]` table checked and settled
/// (see the `law` module), with the rover's data it reads.
#[derive(Clone, Debug)]
pub struct Controller {
    speed: Option<SpeedLaw>,
    steering: SteeringLaw,
    settle: f64,
    left: Vec<bool>,
    rest_xy: Vec<(f64, f64)>,
    steerable: Vec<bool>,
    max_torque: Vec<f64>,
    /// Each motor's torque–speed line, when the description gives one.
    motor_curves: Vec<Option<MotorCurve>>,
    /// Each wheel's radius \[m\]: on a soil the speed loop reads the
    /// wheels' rim speeds.
    radii: Vec<f64>,
    /// The largest motor limit [N·m]: where the integrals stop (anti-windup).
    torque_cap: f64,
    active: Option<ActiveSuspension>,
    neutral: Vec<f64>,
    /// The heading hold's current leg of its waypoints.
    leg: usize,
    /// Indices in ζ of the heading hold's integrals, when it has them.
    heading_state: Option<usize>,
    line_state: Option<usize>,
    /// The open-loop command schedule, when the configuration has one.
    schedule: Option<CommandSchedule>,
}

/// Name of the speed loop's integral state (always ζ's first).
pub const SPEED_INTEGRAL: &str = "zeta";
/// Name of the heading hold's heading-error integral state.
pub const HEADING_INTEGRAL: &str = "zeta_heading";
/// Name of the heading hold's line-offset integral state.
pub const LINE_INTEGRAL: &str = "zeta_line";

impl Controller {
    /// A controller for `model`; commands start after `settle` seconds. A
    /// command file is read relative to the working directory.
    pub fn new(config: ControllerConfig, model: &Model, settle: f64) -> Result<Self, ControlError> {
        Self::new_in(config, model, settle, std::path::Path::new("."))
    }

    /// [`Controller::new`], with a command file read relative to `base_dir`
    /// (the scenario's folder). Every check of the `[control]` table is
    /// here: a controller that is built runs without re-reading it.
    pub fn new_in(
        config: ControllerConfig,
        model: &Model,
        settle: f64,
        base_dir: &std::path::Path,
    ) -> Result<Self, ControlError> {
        let rest = model.rest();
        let rest_xy: Vec<(f64, f64)> = model
            .rest_wheel_centres()
            .iter()
            .map(|u| (u[0], u[1]))
            .collect();
        let steerable: Vec<bool> = model.wheels.iter().map(|w| w.steerable).collect();
        let speed = match config.speed {
            Some(s) => Some(speed_law(s, model)?),
            None => None,
        };
        let (heading_state, line_state) = match &config.steering {
            Steering::Heading(h) => {
                let heading = h.integrates_heading().then_some(1);
                let line = h
                    .integrates_line()
                    .then_some(1 + usize::from(heading.is_some()));
                (heading, line)
            }
            _ => (None, None),
        };
        let steering = steering_law(config.steering, speed.is_some(), &rest_xy, &steerable)?;
        let active = match &config.active_suspension {
            Some(c) => Some(active_suspension(c, model, &rest)?),
            None => None,
        };
        let schedule = match &config.commands {
            Some(c) => Some(
                CommandSchedule::load(c, base_dir, model).map_err(|m| err("commands.file", m))?,
            ),
            None => None,
        };
        Ok(Self {
            speed,
            steering,
            schedule,
            heading_state,
            line_state,
            left: rest_xy.iter().map(|&(_, y)| y > 0.0).collect(),
            rest_xy,
            steerable,
            max_torque: model.wheels.iter().map(|w| w.max_torque).collect(),
            motor_curves: model.wheels.iter().map(|w| w.motor_curve).collect(),
            radii: model.wheels.iter().map(|w| w.radius).collect(),
            torque_cap: model
                .wheels
                .iter()
                .map(|w| w.max_torque)
                .fold(0.0, f64::max),
            active,
            neutral: model.coordinates.iter().map(|c| c.neutral).collect(),
            settle,
            leg: 0,
        })
    }

    /// Time commands start (end of settling) \[s\].
    pub fn settle_time(&self) -> f64 {
        self.settle
    }

    /// Which wheels steer (the description's order).
    pub fn steerable(&self) -> &[bool] {
        &self.steerable
    }

    /// Move spring `coord`'s neutral y0 to `neutral` (an active
    /// suspension's set-point given from outside, as a rig's controller
    /// gives it), in the controller's record and in `plant`; the
    /// integrator should be restarted (a jump of the right-hand side). A
    /// coordinate past the rover's is ignored.
    pub fn set_neutral<P: Plant + ?Sized>(&mut self, coord: usize, neutral: f64, plant: &mut P) {
        if let Some(n) = self.neutral.get_mut(coord) {
            *n = neutral;
            plant.set_spring_neutral(coord, neutral);
        }
    }

    /// The current spring neutrals y0 (moved by the active suspension).
    pub fn neutrals(&self) -> &[f64] {
        &self.neutral
    }

    /// Hold the speed set-point at `speed` [m/s] from now on (after
    /// settling), in place of the scenario's profile: how a step-wise
    /// caller (a Python loop, a learning agent) steers the speed loop
    /// without rebuilding the controller. Allocates nothing.
    pub fn set_speed(&mut self, speed: f64) -> Result<(), ControlError> {
        if !speed.is_finite() {
            return Err(err("speed.speed", format!("must be finite, got {speed}")));
        }
        match &mut self.speed {
            Some(s) => {
                s.speed = Profile::Constant(speed);
                Ok(())
            }
            None => Err(err(
                "speed",
                "this run has no speed loop; add `[control.speed]` to the scenario",
            )),
        }
    }

    /// Hold the steering set-point at `value` from now on: the torque
    /// difference Δτ [N·m] of slip steering, the turning radius \[m\] of
    /// Ackermann steering by radius, or its front-left angle [°]; like
    /// [`Controller::set_speed`], in place of the scenario's profile.
    pub fn set_steering_setpoint(&mut self, value: f64) -> Result<(), ControlError> {
        if !value.is_finite() {
            return Err(err("steering", format!("must be finite, got {value}")));
        }
        match &mut self.steering {
            SteeringLaw::Slip { delta_tau } => *delta_tau = Profile::Constant(value),
            SteeringLaw::Ackermann { curvature, .. } => {
                let angle = matches!(curvature, CurvatureCommand::Angle { .. });
                check_ackermann(&Profile::Constant(value), angle)?;
                curvature.hold(value)
            }
            _ => {
                return Err(err(
                    "steering",
                    "a steering set-point needs slip or Ackermann steering (`kind = \"slip\"` or `\"ackermann\"`)",
                ));
            }
        }
        Ok(())
    }

    /// Speed set-point V(t) [m/s]: zero while settling.
    pub fn speed_setpoint(&self, t: f64) -> f64 {
        match &self.speed {
            Some(s) if t >= self.settle => s.speed.at(t - self.settle),
            _ => 0.0,
        }
    }

    /// Number of the controller's integral states ζ, the last entries of
    /// the state `y = [x; w; ζ]`: the speed loop's (always, first; it acts
    /// only with a gain `ki`), then the heading hold's heading-error and
    /// line-offset integrals, each when its gain is set.
    pub fn states(&self) -> usize {
        1 + usize::from(self.heading_state.is_some()) + usize::from(self.line_state.is_some())
    }

    /// The integral states' names ([`SPEED_INTEGRAL`], [`HEADING_INTEGRAL`],
    /// [`LINE_INTEGRAL`]) in ζ's order, each with whether it acts on the
    /// rover (the speed loop's does only with `ki > 0`).
    pub fn state_names(&self) -> Vec<(&'static str, bool)> {
        let speed = self.speed.as_ref().is_some_and(|s| s.ki > 0.0);
        let mut names = vec![(SPEED_INTEGRAL, speed)];
        if self.heading_state.is_some() {
            names.push((HEADING_INTEGRAL, true));
        }
        if self.line_state.is_some() {
            names.push((LINE_INTEGRAL, true));
        }
        names
    }

    /// The heading hold's integrals in `z` (ζ).
    fn heading_integrals(&self, z: &[f64]) -> HeadingIntegrals {
        let at = |i: Option<usize>| i.and_then(|i| z.get(i)).copied().unwrap_or(0.0);
        HeadingIntegrals {
            heading: at(self.heading_state),
            line: at(self.line_state),
        }
    }

    /// The speed the speed loop holds: the body's forward speed v_x on
    /// rigid ground (the paper's loop); on a soil (wheel spins `spins`
    /// given), the wheels' mean rim speed r·ω, as a rover's own drive holds
    /// its wheels' rates (each wheel's torque then also gets
    /// `K_p·(v̄ − r·ω_j)`, so that each holds the mean): a wheel in soft
    /// soil does not run away, and a rover that cannot climb stalls with its
    /// wheels turning at the set-point (slip 1), as Spirit did.
    pub fn measured_speed(&self, w: &[f64], spins: &[f64]) -> f64 {
        if spins.is_empty() {
            return w[0];
        }
        let sum: f64 = spins.iter().zip(&self.radii).map(|(o, r)| o * r).sum();
        sum / spins.len() as f64
    }

    /// Rates of the integral states `z` into `out` (both [`Controller::states`]
    /// long), for coordinates `x`, pseudo-velocities `w` and (on a soil)
    /// the wheels' spins:
    /// - the speed loop's, `V − v` ([`Controller::measured_speed`]);
    /// - the heading error's, e (0 while settling);
    /// - the line offset's, e_y (0 while settling).
    ///
    /// Each is frozen while its term alone saturates what it drives in the
    /// same direction (anti-windup): the largest motor torque for the speed
    /// loop and the torque difference, [`LINE_INTEGRAL_CAP`] for the line.
    pub fn integral_rates(
        &self,
        t: f64,
        (x, w, z, spins): (&[f64], &[f64], &[f64], &[f64]),
        out: &mut [f64],
    ) {
        out.iter_mut().for_each(|o| *o = 0.0);
        let cap = self.torque_cap;
        let hold = |e: f64, held: f64, cap: f64| {
            if (held >= cap && e > 0.0) || (held <= -cap && e < 0.0) {
                0.0
            } else {
                e
            }
        };
        if let Some(s) = &self.speed {
            out[0] = hold(
                self.speed_setpoint(t) - self.measured_speed(w, spins),
                s.ki * z[0],
                cap,
            );
        }
        let SteeringLaw::Heading {
            hold: h, heading, ..
        } = &self.steering
        else {
            return;
        };
        if t < self.settle {
            return;
        }
        let line = h.line_with(heading.at(t - self.settle), self.leg);
        let integrals = self.heading_integrals(z);
        let position = [x[0], x[1]];
        if let Some(i) = self.heading_state {
            let e = h.error(line, position, x[5], integrals.line);
            out[i] = hold(e, h.ki.unwrap_or(0.0) * integrals.heading, cap);
        }
        if let Some(i) = self.line_state {
            let e_y = h.line_offset(line, position);
            let held = h.cross_track_integral * integrals.line;
            out[i] = hold(e_y, held, LINE_INTEGRAL_CAP);
        }
    }

    /// Motor torques per wheel [N·m] from the speed the loop holds
    /// ([`Controller::measured_speed`]: `w[0]`, or on a soil the rim
    /// speeds of the wheels spinning at `spins`), the
    /// integral states `z` (ζ), the wheels' normal loads `normals` and
    /// longitudinal slips `slips` (this evaluation; `slips` is only read by
    /// the anti-spin distribution, [`Controller::reads_slip`], and may be
    /// empty otherwise), plus the open-loop commands `commanded` (an external
    /// controller's, one per wheel), all within each motor's limit at the
    /// wheel's spin rate `rates[k]` [rad/s] ([`Wheel::torque_limits`]:
    /// `max_torque`, narrowed by the motor's torque–speed line when it has
    /// one; `rates` is only read then, and may be empty otherwise); heading
    /// hold also reads the attitude `x[3..6]` and the angular velocity
    /// `w[3..6]`.
    ///
    /// [`Wheel::torque_limits`]: rover_dynamics::model::Wheel::torque_limits
    #[allow(clippy::too_many_arguments)]
    pub fn torques(
        &self,
        t: f64,
        (x, w, z, spins): (&[f64], &[f64], &[f64], &[f64]),
        (normals, slips): (&[f64], &[f64]),
        commanded: &[f64],
        rates: &[f64],
        out: &mut [f64],
    ) {
        out.copy_from_slice(commanded);
        let speed = self.measured_speed(w, spins);
        self.add_torques(t, (x, w, z), speed, (normals, slips), out);
        // On a soil each wheel's own rate is held too, about the mean: a
        // lightly loaded wheel does not spin out while the others stall.
        if let Some(s) = &self.speed {
            for ((o, spin), r) in out.iter_mut().zip(spins).zip(&self.radii) {
                *o += s.kp * (speed - r * spin);
            }
        }
        if let Some(s) = &self.schedule
            && t >= self.settle
        {
            s.add_torques(t - self.settle, out);
        }
        for (k, (o, &cap)) in out.iter_mut().zip(&self.max_torque).enumerate() {
            *o = match &self.motor_curves[k] {
                None => o.clamp(-cap, cap),
                Some(curve) => {
                    let (lo, hi) = curve.limits(rates[k]);
                    o.clamp(lo.max(-cap), hi.min(cap))
                }
            };
        }
    }

    /// Each wheel's radius \[m\], in the description's order.
    pub fn radii(&self) -> &[f64] {
        &self.radii
    }

    /// Whether any motor has a torque–speed line: then
    /// [`Controller::torques`] reads the wheels' spin rates.
    pub fn has_motor_curves(&self) -> bool {
        self.motor_curves.iter().any(Option::is_some)
    }

    /// Whether the speed loop's distribution reads the wheels' slips (the
    /// anti-spin distribution): then [`Controller::torques`] needs them.
    pub fn reads_slip(&self) -> bool {
        self.speed.as_ref().is_some_and(SpeedLaw::reads_slip)
    }

    /// The built-in loops' torques, added to `out`.
    fn add_torques(
        &self,
        t: f64,
        (x, w, z): (&[f64], &[f64], &[f64]),
        speed: f64,
        (normals, slips): (&[f64], &[f64]),
        out: &mut [f64],
    ) {
        let Some(s) = &self.speed else {
            return;
        };
        let tau0 = s.kp * (self.speed_setpoint(t) - speed) + s.ki * z[0];
        s.add_shares(tau0, normals, slips, out);
        let settled = t >= self.settle;
        let dt = match &self.steering {
            SteeringLaw::Slip { delta_tau } => Some(if settled {
                delta_tau.at(t - self.settle)
            } else {
                0.0
            }),
            SteeringLaw::Heading {
                hold: h, heading, ..
            } if h.via == HeadingActuator::Slip => Some(if settled {
                let att = rover_dynamics::attitude::Attitude::new(x[3], x[4], x[5]);
                let psi_rate = att.rates([w[3], w[4], w[5]])[2];
                h.delta_tau(
                    h.line_with(heading.at(t - self.settle), self.leg),
                    [x[0], x[1]],
                    x[5],
                    psi_rate,
                    self.heading_integrals(z),
                )
            } else {
                0.0
            }),
            _ => None,
        };
        if let Some(dt) = dt {
            for (o, &left) in out.iter_mut().zip(&self.left) {
                *o += if left { -dt } else { dt };
            }
        }
    }

    /// Steering angles δ_j \[rad\] at time t for coordinates `x` and
    /// integral states `z` (a heading hold via Ackermann reads G's X, Y, the
    /// heading ψ and its line integral).
    pub fn steer(&self, t: f64, x: &[f64], z: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|o| *o = 0.0);
        if t < self.settle {
            return;
        }
        let tc = t - self.settle;
        if let Some(s) = &self.schedule {
            s.add_steering(tc, out);
        }
        let (kappa, centre_x) = match &self.steering {
            SteeringLaw::Ackermann {
                curvature,
                centre_x,
            } => (curvature.curvature(tc, *centre_x), *centre_x),
            SteeringLaw::Heading {
                hold: h,
                heading,
                centre_x,
            } if h.via == HeadingActuator::Ackermann => (
                h.curvature(
                    h.line_with(heading.at(tc), self.leg),
                    [x[0], x[1]],
                    x[5],
                    self.heading_integrals(z),
                ),
                *centre_x,
            ),
            _ => return,
        };
        for (k, o) in out.iter_mut().enumerate() {
            if self.steerable[k] {
                let (x, y) = self.rest_xy[k];
                *o += ackermann_angle(kappa, x, y, centre_x);
            }
        }
    }

    /// Commanded path curvature κ = 1/R at time t (Ackermann; 0 otherwise or
    /// while settling), and the turn centre's body x, x_c.
    pub fn curvature(&self, t: f64) -> (f64, f64) {
        let SteeringLaw::Ackermann {
            curvature,
            centre_x,
        } = &self.steering
        else {
            return (0.0, 0.0);
        };
        if t < self.settle {
            return (0.0, *centre_x);
        }
        (curvature.curvature(t - self.settle, *centre_x), *centre_x)
    }

    /// Kinematic turning radius R_k = sqrt(x_c² + R²) at time t, when steering
    /// kinematically with a non-zero curvature.
    pub fn kinematic_radius(&self, t: f64) -> Option<f64> {
        let SteeringLaw::Ackermann {
            curvature,
            centre_x,
        } = &self.steering
        else {
            return None;
        };
        let tc = (t - self.settle).max(0.0);
        let r = match curvature {
            CurvatureCommand::Radius(r) => r.at(tc),
            CurvatureCommand::Angle { .. } => {
                let kappa = curvature.curvature(tc, *centre_x);
                if kappa == 0.0 {
                    return None;
                }
                1.0 / kappa
            }
        };
        (r != 0.0 && r.is_finite()).then(|| (centre_x * centre_x + r * r).sqrt())
    }

    /// Period of the sampled part (active suspension), if any.
    pub fn sample_period(&self) -> Option<f64> {
        let legs =
            matches!(&self.steering, SteeringLaw::Heading { hold, .. } if hold.waypoints.len() > 2);
        match &self.active {
            Some(a) => Some(a.config.sample_time),
            None if legs => Some(crate::control::LEG_CHECK_PERIOD),
            None => None,
        }
    }

    /// The heading hold's current leg of its waypoints (0 without them).
    pub fn leg(&self) -> usize {
        self.leg
    }

    /// Times at which commands jump (step profiles, end of settling).
    pub fn breakpoints(&self) -> Vec<f64> {
        let mut b = vec![self.settle];
        let shift = |v: Vec<f64>| v.into_iter().map(|t| t + self.settle);
        if let Some(s) = &self.speed {
            b.extend(shift(s.speed.breakpoints()));
        }
        match &self.steering {
            SteeringLaw::Slip { delta_tau } => b.extend(shift(delta_tau.breakpoints())),
            SteeringLaw::Heading { heading, .. } => b.extend(shift(heading.breakpoints())),
            SteeringLaw::Ackermann { curvature, .. } => {
                b.extend(shift(curvature.profile().breakpoints()))
            }
            SteeringLaw::None => {}
        }
        if let Some(s) = &self.schedule {
            b.extend(shift(s.breakpoints()));
        }
        b
    }

    /// The sampled update at time t: the active suspension (eq. 42) moves
    /// the plant's spring neutrals, a heading hold on waypoints moves on to
    /// its next leg once G has passed the end of its current one. Inactive
    /// while settling. Returns whether anything changed (the integrator
    /// restarts then).
    pub fn sample<P: Plant + ?Sized>(
        &mut self,
        t: f64,
        x: &[f64],
        w: &[f64],
        plant: &mut P,
    ) -> bool {
        if t < self.settle {
            return false;
        }
        let mut changed = false;
        if let SteeringLaw::Heading { hold: h, .. } = &self.steering {
            while h.passed(self.leg, [x[0], x[1]]) {
                self.leg += 1;
                changed = true;
            }
        }
        let Some(active) = &mut self.active else {
            return changed;
        };
        let att = rover_dynamics::attitude::Attitude::new(x[3], x[4], x[5]);
        let rates = att.rates([w[3], w[4], w[5]]);
        active.update(x[4], rates[1], x[3], rates[0], &x[6..], &mut self.neutral);
        for (i, &n) in self.neutral.iter().enumerate() {
            plant.set_spring_neutral(i, n);
        }
        true
    }
}

/// The speed loop, checked: its profile and non-negative finite gains; the
/// static loads found once when it shares by them.
fn speed_law(s: SpeedConfig, model: &Model) -> Result<SpeedLaw, ControlError> {
    s.speed.validate().map_err(|m| err("speed.speed", m))?;
    if !(s.kp.is_finite() && s.kp >= 0.0 && s.ki.is_finite() && s.ki >= 0.0) {
        return Err(err(
            "speed",
            format!(
                "gains must be finite and ≥ 0, got kp = {}, ki = {}",
                s.kp, s.ki
            ),
        ));
    }
    let anti_spin = anti_spin_parameters(&s)?;
    SpeedLaw::new(s.speed, (s.kp, s.ki), s.distribution, anti_spin, || {
        flat_ground_loads(model)
    })
    .map_err(|e| {
        err(
            "speed.distribution",
            format!("cannot find the static loads: {e}"),
        )
    })
}

/// The anti-spin distribution's slip threshold and band, checked (the
/// defaults when not given); either given with another distribution is an
/// error.
fn anti_spin_parameters(s: &SpeedConfig) -> Result<(f64, f64), ControlError> {
    let threshold = s.slip_threshold.unwrap_or(DEFAULT_SLIP_THRESHOLD);
    let band = s.slip_band.unwrap_or(DEFAULT_SLIP_BAND);
    if s.distribution != Distribution::AntiSpin {
        for (field, given) in [
            ("speed.slip_threshold", s.slip_threshold),
            ("speed.slip_band", s.slip_band),
        ] {
            if given.is_some() {
                return Err(err(
                    field,
                    "only the anti-spin distribution reads it: set `distribution = \"anti_spin\"` or remove it",
                ));
            }
        }
    }
    if !(threshold.is_finite() && (0.0..1.0).contains(&threshold)) {
        return Err(err(
            "speed.slip_threshold",
            format!(
                "must lie in [0, 1) (the longitudinal slip 1 − v/(r·ω) above which a wheel's torque is cut), got {threshold}; {DEFAULT_SLIP_THRESHOLD} suits soft soil"
            ),
        ));
    }
    if !(band.is_finite() && band > 0.0) {
        return Err(err(
            "speed.slip_band",
            format!(
                "must be > 0 (the slip beyond `slip_threshold` over which a wheel's share falls to none), got {band}; {DEFAULT_SLIP_BAND} is the default"
            ),
        ));
    }
    Ok((threshold, band))
}

/// The steering, checked and settled: degrees become radians, an Ackermann
/// angle names the wheel it belongs to, the turn centre is placed.
fn steering_law(
    steering: Steering,
    has_speed: bool,
    rest_xy: &[(f64, f64)],
    steerable: &[bool],
) -> Result<SteeringLaw, ControlError> {
    Ok(match steering {
        Steering::None => SteeringLaw::None,
        Steering::Slip { delta_tau } => {
            delta_tau
                .validate()
                .map_err(|m| err("steering.delta_tau", m))?;
            SteeringLaw::Slip { delta_tau }
        }
        Steering::Heading(h) => {
            validate_heading(&h, has_speed, steerable)?;
            let centre_x = if h.via == HeadingActuator::Ackermann {
                heading_centre_x(rest_xy, steerable)
            } else {
                0.0
            };
            SteeringLaw::Heading {
                heading: h.heading_deg.map(f64::to_radians),
                hold: h,
                centre_x,
            }
        }
        Steering::Ackermann(a) => {
            let Some(first) = steerable.iter().position(|&s| s) else {
                return Err(err(
                    "steering",
                    "Ackermann steering needs steerable wheels; this rover has none (use kind = \"slip\")",
                ));
            };
            let curvature = match (a.radius, a.front_left_deg) {
                (Some(p), None) => {
                    p.validate().map_err(|m| err("steering.radius", m))?;
                    check_ackermann(&p, false)?;
                    CurvatureCommand::Radius(p)
                }
                (None, Some(p)) => {
                    p.validate()
                        .map_err(|m| err("steering.front_left_deg", m))?;
                    check_ackermann(&p, true)?;
                    CurvatureCommand::Angle {
                        radians: p.map(f64::to_radians),
                        wheel: rest_xy[first],
                    }
                }
                _ => {
                    return Err(err(
                        "steering",
                        "give exactly one of `radius` (m) or `front_left_deg`",
                    ));
                }
            };
            SteeringLaw::Ackermann {
                curvature,
                centre_x: a
                    .centre_x
                    .unwrap_or_else(|| default_centre_x(rest_xy, steerable)),
            }
        }
    })
}

/// The values of an Ackermann command: a front-left angle strictly
/// between −90° and 90° (at ±90° the wheel stands across its path, and a
/// larger angle is a smaller one turned over), or a turn-centre position
/// R that is not 0 (R is the turn centre's lateral offset: at 0 the rover
/// would turn on a point of its own centre line, with an infinite
/// curvature); a linear table of radii does not change sign between two
/// points (it would pass through 0).
fn check_ackermann(p: &Profile, angle: bool) -> Result<(), ControlError> {
    // The profile's values, without allocating: a set-point is checked on
    // the live loop's path.
    let constant;
    let values: &[[f64; 2]] = match p {
        Profile::Constant(v) => {
            constant = [[0.0, *v]];
            &constant
        }
        Profile::Table { points, .. } => points,
    };
    let mut values = values.iter().map(|p| p[1]);
    if angle {
        if let Some(v) = values.find(|v| v.abs() >= 90.0) {
            return Err(err(
                "steering.front_left_deg",
                format!(
                    "{v}° is not a steering angle: it must lie strictly between -90° and 90° (the angle in degrees of the first steerable wheel, positive turns left)"
                ),
            ));
        }
        return Ok(());
    }
    if values.any(|v| v == 0.0) {
        return Err(err(
            "steering.radius",
            "a radius of 0 m is no turn: `radius` is the turn centre's lateral position R [m], R > 0 turns left and R < 0 right; to drive straight, leave out [control.steering]",
        ));
    }
    if let Profile::Table {
        points,
        interpolation: super::profile::Interpolation::Linear,
    } = p
        && let Some(w) = points
            .windows(2)
            .find(|w| w[0][1].signum() != w[1][1].signum())
    {
        return Err(err(
            "steering.radius",
            format!(
                "the linear radius table goes from {} m to {} m between t = {} s and t = {} s, through R = 0 (a turn of infinite curvature); to turn the other way, step from one sign to the other (interpolation = \"step\")",
                w[0][1], w[1][1], w[0][0], w[1][0]
            ),
        ));
    }
    Ok(())
}

/// The active suspension, checked: a positive sample time, a sprung
/// coordinate to move, the gains its law needs (and none of the other
/// law's); the leveling law settled at the static equilibrium.
fn active_suspension(
    c: &ActiveSuspensionConfig,
    model: &Model,
    rest: &[f64],
) -> Result<ActiveSuspension, ControlError> {
    if !(c.sample_time.is_finite() && c.sample_time > 0.0) {
        return Err(err(
            "active_suspension.sample_time",
            format!("must be > 0 s, got {}", c.sample_time),
        ));
    }
    let sprung: Vec<bool> = model
        .coordinates
        .iter()
        .map(|c| !matches!(c.spring, rover_dynamics::model::Spring::None))
        .collect();
    if !sprung.iter().any(|&s| s) {
        return Err(err(
            "active_suspension",
            "the rover has no sprung coordinate whose neutral could be moved",
        ));
    }
    let eq42 = [
        ("kp_pitch", c.kp_pitch),
        ("kd_pitch", c.kd_pitch),
        ("kp_roll", c.kp_roll),
        ("kd_roll", c.kd_roll),
    ];
    let leveling = [
        ("attitude_gain", c.attitude_gain),
        ("rate_gain", c.rate_gain),
        ("centring_gain", c.centring_gain),
        ("warp_gain", c.warp_gain),
    ];
    let finite = |list: &[(&str, Option<f64>)]| {
        for (name, v) in list {
            if let Some(v) = v
                && !v.is_finite()
            {
                return Err(err(
                    &format!("active_suspension.{name}"),
                    format!("must be finite, got {v}"),
                ));
            }
        }
        Ok(())
    };
    let foreign = |list: &[(&str, Option<f64>)], law: &str, other: &str| match list
        .iter()
        .find(|(_, v)| v.is_some())
    {
        Some((name, _)) => Err(err(
            &format!("active_suspension.{name}"),
            format!(
                "belongs to law = \"{other}\", not to law = \"{law}\"; remove it or set law = \"{other}\""
            ),
        )),
        None => Ok(()),
    };
    match c.law {
        SuspensionLaw::Eq42 => {
            foreign(&leveling, "eq42", "leveling")?;
            finite(&eq42)?;
            for name in ["kp_pitch", "kp_roll"] {
                let v = if name == "kp_pitch" {
                    c.kp_pitch
                } else {
                    c.kp_roll
                };
                if v.is_none() {
                    return Err(err(
                        &format!("active_suspension.{name}"),
                        "the paper's law (eq. 42) gives no gains: set kp_pitch and kp_roll (radians of neutral per radian, per update; e.g. 0.6), or choose law = \"leveling\", whose gains come from the rover",
                    ));
                }
            }
            Ok(ActiveSuspension::new(
                c.clone(),
                &sprung,
                &slopes(model, rest),
                model.coordinates.iter().map(|c| c.min).collect(),
                model.coordinates.iter().map(|c| c.max).collect(),
            ))
        }
        SuspensionLaw::Leveling => {
            foreign(&eq42, "leveling", "eq42")?;
            finite(&leveling)?;
            let in_range = |name: &str, v: Option<f64>, lo: f64, lo_open: bool| {
                if let Some(v) = v
                    && (v > 1.0 || v < lo || (lo_open && v <= lo))
                {
                    let bound = if lo_open { "(0, 1]" } else { "[0, 1]" };
                    return Err(err(
                        &format!("active_suspension.{name}"),
                        format!(
                            "is the fraction of the error removed per update and must lie in {bound}, got {v}; leave it out for the rover's default"
                        ),
                    ));
                }
                Ok(())
            };
            in_range("attitude_gain", c.attitude_gain, 0.0, true)?;
            in_range("centring_gain", c.centring_gain, 0.0, false)?;
            in_range("warp_gain", c.warp_gain, 0.0, false)?;
            if let Some(b) = c.rate_gain
                && b < 0.0
            {
                return Err(err(
                    "active_suspension.rate_gain",
                    format!("must be ≥ 0 s, got {b}"),
                ));
            }
            let y_eq = crate::quasi_static::flat_ground_equilibrium(model).map_err(|e| {
                err(
                    "active_suspension.law",
                    format!(
                        "the leveling law is settled at the static equilibrium on flat ground, which cannot be found: {e}"
                    ),
                )
            })?;
            ActiveSuspension::leveling(c.clone(), model, &y_eq).map_err(|e| {
                err(
                    "active_suspension.law",
                    format!("the leveling law cannot run on this rover: {}", e.0),
                )
            })
        }
    }
}

/// The checks of a heading hold: finite set-point and line, the gains its
/// actuator needs and no other, and what the actuator needs of the rover.
fn validate_heading(
    h: &HeadingHold,
    has_speed: bool,
    steerable: &[bool],
) -> Result<(), ControlError> {
    h.heading_deg
        .validate()
        .map_err(|m| err("steering.heading_deg", m))?;
    non_negative("steering.cross_track", h.cross_track, "rad/m")?;
    non_negative(
        "steering.cross_track_integral",
        h.cross_track_integral,
        "rad/(m·s)",
    )?;
    if h.cross_track_integral > 0.0 && h.cross_track <= 0.0 {
        return Err(err(
            "steering.cross_track_integral",
            "integrates the line offset on top of `cross_track`: set cross_track > 0 too (an integral alone makes the line loop oscillate)",
        ));
    }
    if !h.line_origin.iter().all(|v| v.is_finite()) {
        return Err(err(
            "steering.line_origin",
            format!("must be finite, got {:?}", h.line_origin),
        ));
    }
    if !h.waypoints.is_empty() {
        if h.waypoints.len() < 2 {
            return Err(err(
                "steering.waypoints",
                "give at least two waypoints [[X, Y], …] (one leg), or none",
            ));
        }
        if !h.waypoints.iter().flatten().all(|v| v.is_finite()) {
            return Err(err("steering.waypoints", "every coordinate must be finite"));
        }
        if let Some(k) = h.waypoints.windows(2).position(|p| p[0] == p[1]) {
            return Err(err(
                "steering.waypoints",
                format!(
                    "waypoints {} and {} coincide: a leg needs a length",
                    k + 1,
                    k + 2
                ),
            ));
        }
        if h.heading_deg != Profile::Constant(0.0) || h.line_origin != [0.0, 0.0] {
            return Err(err(
                "steering.waypoints",
                "waypoints replace `heading_deg` and `line_origin`: give one or the other",
            ));
        }
    }
    match h.via {
        HeadingActuator::Slip => {
            let Some(kp) = h.kp else {
                return Err(err(
                    "steering.kp",
                    "missing: the torque difference per radian of heading error [N·m/rad] (or via = \"ackermann\" with a `lookahead`)",
                ));
            };
            if !(kp.is_finite() && kp > 0.0) {
                return Err(err("steering.kp", format!("must be > 0 N·m/rad, got {kp}")));
            }
            non_negative("steering.kd", h.kd.unwrap_or(0.0), "N·m·s/rad")?;
            non_negative("steering.ki", h.ki.unwrap_or(0.0), "N·m/(rad·s)")?;
            if h.lookahead.is_some() {
                return Err(err(
                    "steering.lookahead",
                    "only for via = \"ackermann\"; slip steering takes `kp`, `ki` and `kd`",
                ));
            }
            if !has_speed {
                return Err(err(
                    "steering",
                    "heading hold by slip steers by a torque difference on top of the speed loop's torque: add a [control.speed] table",
                ));
            }
        }
        HeadingActuator::Ackermann => {
            if !steerable.iter().any(|&s| s) {
                return Err(err(
                    "steering",
                    "heading hold via = \"ackermann\" needs steerable wheels; this rover has none (use via = \"slip\")",
                ));
            }
            let Some(l) = h.lookahead else {
                return Err(err(
                    "steering.lookahead",
                    "missing: the distance ahead [m] at which the steering meets the commanded heading (about twice the wheelbase)",
                ));
            };
            if !(l.is_finite() && l > 0.0) {
                return Err(err("steering.lookahead", format!("must be > 0 m, got {l}")));
            }
            if h.kp.is_some() || h.kd.is_some() || h.ki.is_some() {
                return Err(err(
                    "steering.kp",
                    "`kp`, `ki` and `kd` are the slip law's gains; via = \"ackermann\" steers by `lookahead` (and `cross_track`, `cross_track_integral` for a line)",
                ));
            }
        }
    }
    Ok(())
}

/// A gain that must be finite and ≥ 0, with its field and unit.
fn non_negative(field: &str, value: f64, unit: &str) -> Result<(), ControlError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(err(field, format!("must be ≥ 0 {unit}, got {value}")))
    }
}

/// x_c of a heading hold via Ackermann: the mean rest x of the
/// non-steerable wheels, or, when all steer, of all wheels (front and rear
/// steer opposite ways; Ackermann steering's default would hold one axle
/// straight on a four-wheeler whose axles are equally far from G). The
/// live drive loop steers about the same centre.
pub fn heading_centre_x(rest_xy: &[(f64, f64)], steerable: &[bool]) -> f64 {
    fixed_mean_x(rest_xy, steerable)
        .unwrap_or_else(|| rest_xy.iter().map(|p| p.0).sum::<f64>() / rest_xy.len().max(1) as f64)
}

/// Default x_c: the mean rest x of the non-steerable wheels, or, when all
/// steer, the rest x of the wheel nearest to G along x.
fn default_centre_x(rest_xy: &[(f64, f64)], steerable: &[bool]) -> f64 {
    fixed_mean_x(rest_xy, steerable).unwrap_or_else(|| {
        rest_xy
            .iter()
            .map(|p| p.0)
            .min_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap_or(0.0)
    })
}

/// The mean rest x of the non-steerable wheels; `None` when all steer.
fn fixed_mean_x(rest_xy: &[(f64, f64)], steerable: &[bool]) -> Option<f64> {
    let fixed: Vec<f64> = rest_xy
        .iter()
        .zip(steerable)
        .filter(|(_, s)| !**s)
        .map(|(p, _)| p.0)
        .collect();
    (!fixed.is_empty()).then(|| fixed.iter().sum::<f64>() / fixed.len() as f64)
}

/// Per coordinate: each wheel's rest (x, y) and ∂u_z/∂y_i at rest.
fn slopes(model: &Model, rest: &[f64]) -> Vec<Vec<(f64, f64, f64)>> {
    let m = model.m();
    let mut out = vec![Vec::new(); m];
    for w in &model.wheels {
        let body = &model.bodies[w.body];
        let mut dz = vec![0.0; m];
        let u = body.position.eval(rest, |i, d1, _| dz[i] += d1[2]);
        for i in 0..m {
            if dz[i] != 0.0 {
                out[i].push((u[0], u[1], dz[i]));
            }
        }
    }
    out
}
