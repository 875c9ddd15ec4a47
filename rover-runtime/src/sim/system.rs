//! The rover as a first-order ODE system `ẏ = f(t, y)`, `y = [x; w; ζ; ω]`
//! (ζ: the controller's integral states, [`Controller::states`]: the speed
//! loop's, then a heading hold's when it integrates, none in a system
//! built by [`RoverSystem::open_loop`]; ω: each wheel's spin rate on a
//! soil, none on rigid ground, [`Ground::spin_states`]).

use rover_dynamics::HeightField;
use rover_dynamics::Model;
use rover_dynamics::kinematics::position_rates;
use rover_dynamics::plant::{Plant, WheelLoad, WheelState};
use rover_dynamics::wheel_ground::WheelReport;

use crate::control::{ControlError, Controller, ControllerConfig};
use crate::ground::Ground;
use rover_integrate::OdeSystem;

use super::error::{CommandError, RunError, SimError};
use super::profile::{Lap, RhsProfile};

mod jacobian;

use jacobian::JacobianWork;

/// Plant, ground and controller, with every buffer a right-hand side needs
/// (sized once: an evaluation allocates nothing).
#[derive(Clone, Debug)]
pub struct RoverSystem<P, H> {
    /// The plant (generic or generated).
    pub plant: P,
    /// The ground; `None` for free flight.
    pub ground: Option<Ground<H>>,
    /// The controller.
    pub control: Controller,
    n: usize,
    /// The controller's integral states in the state (its
    /// [`Controller::states`]; none in an open-loop system).
    integrals: usize,
    /// Spin states (one per wheel on a soil, else none).
    spins: usize,
    /// The rover's gravity g [m/s²], when the system was built from its
    /// description ([`RoverSystem::open_loop`]).
    gravity: Option<f64>,
    /// Built by [`RoverSystem::open_loop`]: the controller has no loop.
    open_loop: bool,
    wheels: Vec<WheelState>,
    loads: Vec<WheelLoad>,
    reports: Vec<WheelReport>,
    torques: Vec<f64>,
    /// Each wheel's spin rate [rad/s] for the motors' torque–speed lines
    /// (filled only when a motor has one).
    motor_rates: Vec<f64>,
    steer: Vec<f64>,
    normals: Vec<f64>,
    /// Each wheel's longitudinal slip (filled only when the controller
    /// reads it: the anti-spin distribution on a soil).
    slips: Vec<f64>,
    torque_commands: Vec<f64>,
    steer_commands: Vec<f64>,
    next_break: f64,
    /// Where the right-hand sides' time goes, when asked for.
    profile: Option<RhsProfile>,
    /// Buffers of the assembled Jacobian ([`OdeSystem::jacobian`]).
    jacobian_work: JacobianWork,
    /// The error scale of each kind of component ([`OdeSystem::error_scale`]).
    error_scale: ErrorScale,
}

/// The error scales of a rover's state, per kind of component, in SI units
/// ([`OdeSystem::error_scale`]): an adaptive integrator without an `atol`
/// controls each component's local error to `rtol·(scale + |y_i|)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ErrorScale {
    /// X, Y, Z of G, and the speed loop's and the line hold's integrals \[m, m·s\].
    pub length: f64,
    /// Roll, pitch, yaw, and the heading hold's integral \[rad, rad·s\].
    pub angle: f64,
    /// The body's velocity vx, vy, vz \[m/s\].
    pub velocity: f64,
    /// The body's angular velocity Ωx, Ωy, Ωz and the wheels' spins on a
    /// soil \[rad/s\].
    pub angular_rate: f64,
}

impl ErrorScale {
    /// The defaults: with BDF's default `rtol` (1e-4), absolute tolerances
    /// of 0.1 µm, 1 µrad, 10 µm/s and 0.1 mrad/s, which hold the paper's
    /// runs within 1 mm and 0.01° of tight-tolerance runs
    /// (docs/PERFORMANCE.md, "Integrators").
    pub const DEFAULT: Self = Self {
        length: 1e-3,
        angle: 1e-2,
        velocity: 1e-1,
        angular_rate: 1.0,
    };
}

impl Default for ErrorScale {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl<P: Plant, H: HeightField> RoverSystem<P, H> {
    /// Assemble a system.
    pub fn new(mut plant: P, ground: Option<Ground<H>>, control: Controller) -> Self {
        let n = plant.dof();
        let k = plant.wheel_count();
        let spins = ground.as_ref().map_or(0, Ground::spin_states);
        let integrals = control.states();
        let dim = 2 * n + integrals + spins;
        Self {
            jacobian_work: JacobianWork::new(&mut plant, n, k, dim),
            plant,
            ground,
            n,
            integrals,
            spins,
            gravity: None,
            open_loop: false,
            wheels: vec![WheelState::default(); k],
            loads: vec![WheelLoad::default(); k],
            reports: vec![WheelReport::default(); k],
            torques: vec![0.0; k],
            motor_rates: vec![0.0; k],
            steer: vec![0.0; k],
            normals: vec![0.0; k],
            slips: vec![0.0; k],
            torque_commands: vec![0.0; k],
            steer_commands: vec![0.0; k],
            control,
            next_break: f64::INFINITY,
            profile: None,
            error_scale: ErrorScale::DEFAULT,
        }
    }

    /// The rover of `model` on `ground` with a controller that has no loop
    /// (no speed loop, no steering law, passive suspension): the motors
    /// give only the open-loop commands ([`RoverSystem::set_torques`],
    /// [`RoverSystem::set_steering`]) and the state is `y = [x; w; ω]`,
    /// without the integral states a loop would add. What an observer runs
    /// beside the rover: the rover's own computer closes the loops, and
    /// the observer is told the commands it issued. Its `control` stays
    /// without loops: the state has no room for their integrals.
    pub fn open_loop(
        plant: P,
        ground: Option<Ground<H>>,
        model: &Model,
    ) -> Result<Self, ControlError> {
        let control = Controller::new(ControllerConfig::default(), model, 0.0)?;
        let mut system = Self::new(plant, ground, control);
        system.integrals = 0;
        system.gravity = Some(model.gravity);
        system.open_loop = true;
        let dim = system.dim();
        system.jacobian_work =
            JacobianWork::new(&mut system.plant, system.n, system.wheels.len(), dim);
        Ok(system)
    }

    /// The rover's gravity g [m/s²] (along −Z), known to a system built by
    /// [`RoverSystem::open_loop`] from the description; `None` otherwise.
    pub fn gravity(&self) -> Option<f64> {
        self.gravity
    }

    /// The error scales an adaptive integrator without `atol` controls
    /// this system's error with ([`ErrorScale`]).
    pub fn error_scales(&self) -> ErrorScale {
        self.error_scale
    }

    /// Sets the error scales (each positive and finite; others are
    /// replaced by the integrator's fallback). Takes effect at the
    /// integrator's next start or restart.
    pub fn set_error_scales(&mut self, scale: ErrorScale) {
        self.error_scale = scale;
    }

    /// Times the parts of every right-hand side from now on (see
    /// [`RhsProfile`]); reading the clock costs a few percent of one.
    pub fn enable_profile(&mut self) {
        self.profile = Some(RhsProfile::default());
    }

    /// The time spent in each part of the right-hand sides since
    /// [`RoverSystem::enable_profile`], if it was called.
    pub fn profile(&self) -> Option<RhsProfile> {
        self.profile
    }

    /// The next time the commands jump (a breakpoint of a profile, the end
    /// of settling), or `None`. Until it is cleared, an evaluation at or
    /// after it takes the commands just before it, their left limit: the
    /// step of an implicit integrator that ends on a breakpoint evaluates
    /// the right-hand side there, and with the command after the jump its
    /// error estimate would not shrink below the jump times the step (at
    /// tight tolerances, below the minimum step). The run driver sets it
    /// while it advances to a breakpoint and restarts the integrator there.
    pub fn set_next_break(&mut self, t: Option<f64>) {
        self.next_break = t.unwrap_or(f64::INFINITY);
    }

    /// Open-loop motor torques [N·m] per wheel (the description's order,
    /// positive drives forward), added to the controller's and held until
    /// the next call: how an external controller (a hardware-in-the-loop
    /// rig's, a user's own) drives the rover, with the built-in loops off
    /// (no `[control.speed]`) or on top of them. The sum is limited to each
    /// motor's `max_torque`. Zero until set. A variable-step integrator
    /// should be restarted after a change (a jump of the right-hand side);
    /// the fixed-step ones need nothing. Allocates nothing.
    pub fn set_torques(&mut self, torques: &[f64]) -> Result<(), CommandError> {
        check_command("torques", torques, self.torque_commands.len())?;
        self.torque_commands.copy_from_slice(torques);
        Ok(())
    }

    /// Open-loop steering angles \[rad\] per wheel, added to the
    /// controller's (positive turns the wheel left, about the body's z);
    /// a wheel that is not steerable takes 0 only. Held, like
    /// [`RoverSystem::set_torques`].
    pub fn set_steering(&mut self, angles: &[f64]) -> Result<(), CommandError> {
        check_command("steering", angles, self.steer_commands.len())?;
        if let Some(k) =
            (0..angles.len()).find(|&k| !self.control.steerable()[k] && angles[k] != 0.0)
        {
            return Err(CommandError::NotSteerable {
                wheel: k + 1,
                value: angles[k],
            });
        }
        self.steer_commands.copy_from_slice(angles);
        Ok(())
    }

    /// The open-loop commands in force: torques [N·m] and steering angles
    /// \[rad\] per wheel.
    pub fn commands(&self) -> (&[f64], &[f64]) {
        (&self.torque_commands, &self.steer_commands)
    }

    /// Evaluate the system at (t, y), as a run does at each output
    /// instant: the wheel states, contact reports and torques that a row
    /// reads are then those of (t, y). `scratch` takes ẏ.
    pub fn evaluate_at(&mut self, t: f64, y: &[f64], scratch: &mut [f64]) -> Result<(), RunError> {
        self.rhs(t, y, scratch).map_err(|e| RunError::Integration {
            t,
            message: e.to_string(),
            step_control: false,
        })
    }

    /// Number of generalized coordinates N.
    pub fn dof(&self) -> usize {
        self.n
    }

    /// Where the wheels' spins start in the state, and how many there are
    /// (one per wheel on a soil, none on rigid ground).
    pub fn spin_range(&self) -> core::ops::Range<usize> {
        let start = 2 * self.n + self.integrals;
        start..start + self.spins
    }

    /// Sets the wheels' spins in `y` to rolling without slip at the wheel
    /// centres' velocities of `y` (r·ω = V·heading, the heading
    /// `a_w × e_Z`): where a run on a soil starts. Nothing on rigid ground.
    pub fn roll_spins(&mut self, t: f64, y: &mut [f64]) {
        let range = self.spin_range();
        if range.is_empty() {
            return;
        }
        let t = self.command_time(t);
        let (x, w, z, _) = self.parts(y);
        self.place_wheels(t, x, w, z);
        let radii = self.ground.as_ref().map_or(&[][..], |g| g.radii());
        for ((spin, s), r) in y[range].iter_mut().zip(&self.wheels).zip(radii) {
            *spin = rolling_rate(s.spin_axis, s.velocity, *r);
        }
    }

    /// Each wheel's spin rate into `motor_rates`, for the motors'
    /// torque–speed lines: the spin state on a soil; on rigid ground (no
    /// spin state: the tyre rolls) the rate of rolling at the centre's
    /// velocity, its speed along the wheel's heading over the radius.
    fn fill_motor_rates(&mut self, spins: &[f64]) {
        if !self.control.has_motor_curves() {
            return;
        }
        if spins.is_empty() {
            let radii = self.control.radii();
            for ((o, s), r) in self.motor_rates.iter_mut().zip(&self.wheels).zip(radii) {
                *o = rolling_rate(s.spin_axis, s.velocity, *r);
            }
        } else {
            self.motor_rates.copy_from_slice(spins);
        }
    }

    /// Each wheel's spin rate \[rad/s\] at the last evaluation, of state
    /// `y`, into `out`: the spin state on a soil; on rigid ground, where the
    /// tyre rolls, the speed of its centre along its heading over the
    /// radius (0 in free flight). What a wheel encoder differentiates.
    pub fn wheel_spin_rates(&self, y: &[f64], out: &mut [f64]) {
        let range = self.spin_range();
        if !range.is_empty() {
            out.copy_from_slice(&y[range]);
            return;
        }
        let radii = self.ground.as_ref().map_or(&[][..], |g| g.radii());
        out.fill(0.0);
        for ((o, s), r) in out.iter_mut().zip(&self.wheels).zip(radii) {
            *o = rolling_rate(s.spin_axis, s.velocity, *r);
        }
    }

    /// Wheel states of the last evaluation.
    pub fn wheel_states(&self) -> &[WheelState] {
        &self.wheels
    }
    /// Contact reports of the last evaluation.
    pub fn reports(&self) -> &[WheelReport] {
        &self.reports
    }
    /// Wheel loads of the last evaluation, as the plant received them.
    pub fn loads(&self) -> &[WheelLoad] {
        &self.loads
    }
    /// Motor torques of the last evaluation [N·m].
    pub fn torques(&self) -> &[f64] {
        &self.torques
    }
    /// Steering angles of the last evaluation \[rad\].
    pub fn steering(&self) -> &[f64] {
        &self.steer
    }

    /// The commands' time for an evaluation at `t`: before the next break,
    /// its left limit on it ([`RoverSystem::set_next_break`]).
    fn command_time(&self, t: f64) -> f64 {
        if t >= self.next_break {
            self.next_break.next_down()
        } else {
            t
        }
    }

    /// A state's parts `(x, w, ζ, ω)`: coordinates, pseudo-velocities,
    /// the controller's integral states and the wheels' spins.
    fn parts<'y>(&self, y: &'y [f64]) -> (&'y [f64], &'y [f64], &'y [f64], &'y [f64]) {
        let (x, rest) = y.split_at(self.n);
        let (w, rest) = rest.split_at(self.n);
        let (z, spins) = rest.split_at(rest.len() - self.spins);
        (x, w, z, spins)
    }

    /// The steering angles (the controller's and the open-loop commands')
    /// and the wheels' kinematics at `(x, w)`, the commands' time `t`.
    fn place_wheels(&mut self, t: f64, x: &[f64], w: &[f64], z: &[f64]) {
        self.control.steer(t, x, z, &mut self.steer);
        for (s, c) in self.steer.iter_mut().zip(&self.steer_commands) {
            *s += c;
        }
        self.plant.wheels(x, w, &self.steer, &mut self.wheels);
    }

    /// The full evaluation: wheels, contacts, control, loads, accelerations.
    fn evaluate(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), SimError> {
        let mut lap = self.profile.is_some().then(Lap::start);
        let mut laps = [0.0; 4];
        let mut mark = |part: usize| {
            if let Some(lap) = &mut lap {
                laps[part] += lap.next();
            }
        };
        let result = self.evaluate_parts(t, y, dy, &mut mark);
        if let Some(p) = &mut self.profile {
            p.evaluations += 1;
            p.wheels_s += laps[0];
            p.contact_s += laps[1];
            p.law_s += laps[2];
            p.plant_s += laps[3];
        }
        result
    }

    /// [`RoverSystem::evaluate`], calling `mark(part)` at the end of each
    /// part: 0 the wheels, 1 the contact search, 2 the law, 3 the plant.
    fn evaluate_parts(
        &mut self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        mark: &mut impl FnMut(usize),
    ) -> Result<(), SimError> {
        let n = self.n;
        let t = self.command_time(t);
        let (x, w, z, spins) = self.parts(y);
        self.place_wheels(t, x, w, z);
        self.fill_motor_rates(spins);
        mark(0);
        match &mut self.ground {
            Some(g) => {
                g.find_contacts(&self.wheels, &mut self.normals)
                    .map_err(SimError::OffMap)?;
                mark(1);
                if self.control.reads_slip() {
                    g.slips(&self.wheels, spins, &mut self.slips);
                }
                self.control.torques(
                    t,
                    (x, w, z, spins),
                    (&self.normals, &self.slips),
                    &self.torque_commands,
                    &self.motor_rates,
                    &mut self.torques,
                );
                g.loads(
                    &self.wheels,
                    &self.torques,
                    spins,
                    &mut self.loads,
                    &mut self.reports,
                );
            }
            None => {
                self.normals.iter_mut().for_each(|v| *v = 0.0);
                // In free flight every wheel spins.
                self.slips.iter_mut().for_each(|v| *v = 1.0);
                self.control.torques(
                    t,
                    (x, w, z, spins),
                    (&self.normals, &self.slips),
                    &self.torque_commands,
                    &self.motor_rates,
                    &mut self.torques,
                );
                self.loads
                    .iter_mut()
                    .for_each(|l| *l = WheelLoad::default());
                for (r, s) in self.reports.iter_mut().zip(&self.wheels) {
                    *r = WheelReport {
                        point: s.centre,
                        ..Default::default()
                    };
                }
            }
        }
        mark(2);
        let (xd, rest) = dy.split_at_mut(n);
        let (wd, rest) = rest.split_at_mut(n);
        let (zd, spin_rates) = rest.split_at_mut(rest.len() - self.spins);
        self.plant
            .derivatives(x, w, &self.loads, xd, wd)
            .map_err(SimError::Plant)?;
        self.control.integral_rates(t, (x, w, z, spins), zd);
        if let Some(g) = &self.ground {
            g.spin_rates(&self.torques, &self.reports, spin_rates);
        }
        mark(3);
        Ok(())
    }
}

/// The spin rate [rad/s] of a wheel of radius `r` rolling without slip at
/// its centre's velocity `v`: the speed along its heading `a_w × e_Z`
/// (horizontal) over the radius; 0 for a wheel lying flat.
fn rolling_rate(a: [f64; 3], v: [f64; 3], r: f64) -> f64 {
    // a_w × e_Z, horizontal.
    let heading = [a[1], -a[0], 0.0];
    let norm = heading[0].hypot(heading[1]);
    if norm > 0.0 {
        (v[0] * heading[0] + v[1] * heading[1]) / (norm * r)
    } else {
        0.0
    }
}

impl<P: Plant, H: HeightField> OdeSystem for RoverSystem<P, H> {
    type Error = SimError;

    fn dim(&self) -> usize {
        2 * self.n + self.integrals + self.spins
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), SimError> {
        self.evaluate(t, y, dy)
    }

    /// The wheels' presses of the last evaluation (at or just before the
    /// step's end) go into the ground's ruts, behind the wheels.
    fn step_accepted(&mut self, _t: f64, _y: &[f64]) {
        if let Some(ground) = &mut self.ground {
            ground.record_ruts(&self.wheels, &self.reports);
        }
    }

    fn split(&self) -> usize {
        self.n
    }

    /// `y = [x; w; ζ; ω]` by kind: G's position on the length scale, the
    /// attitude and the suspension coordinates (rad, or m for a sliding
    /// joint: a metre of travel weighs as a radian) on the angle scale;
    /// the body's velocity on the velocity scale, its angular velocity and
    /// the suspension rates on the angular-rate one; the controller's integrals (m, m·s
    /// or rad·s) on the smaller of length and angle; the wheels' spins on
    /// the angular-rate scale. G's position and the yaw are held to their
    /// absolute tolerance alone: where the rover is, and where it heads,
    /// change nothing in its dynamics, so their size is no measure of
    /// their error.
    fn error_scale(&self, scale: &mut [f64], relative: &mut [f64]) -> bool {
        let ErrorScale {
            length,
            angle,
            velocity,
            angular_rate,
        } = self.error_scale;
        let n = self.n;
        let (x, rest) = scale.split_at_mut(n);
        let (w, rest) = rest.split_at_mut(n);
        let (z, spins) = rest.split_at_mut(self.integrals);
        x[..3].fill(length);
        x[3..6].fill(angle);
        x[6..].fill(angle);
        w[..3].fill(velocity);
        w[3..6].fill(angular_rate);
        w[6..].fill(angular_rate);
        z.fill(length.min(angle));
        spins.fill(angular_rate);
        relative.fill(1.0);
        relative[..3].fill(0.0);
        relative[5] = 0.0;
        true
    }

    fn position_rates(
        &mut self,
        _t: f64,
        y: &[f64],
        dx: &mut [f64],
    ) -> Option<Result<(), SimError>> {
        let n = self.n;
        position_rates(&y[..n], &y[n..2 * n], dx);
        Some(Ok(()))
    }

    /// Assembled from the plant's exact Jacobian and the wheels' load
    /// derivatives (see the `jacobian` module) when the plant has one.
    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut [f64]) -> Option<Result<usize, SimError>> {
        self.assembled_jacobian(t, y, jac)
    }
}

/// One finite value per wheel.
fn check_command(what: &'static str, values: &[f64], wheels: usize) -> Result<(), CommandError> {
    if values.len() != wheels {
        return Err(CommandError::Count {
            what,
            wheels,
            given: values.len(),
        });
    }
    match values.iter().position(|v| !v.is_finite()) {
        Some(k) => Err(CommandError::NotFinite {
            what,
            wheel: k + 1,
            value: values[k],
        }),
        None => Ok(()),
    }
}
