//! The rover's Jacobian `∂f/∂y` assembled from its parts, for the implicit
//! integrators (BDF's Newton iterations, ROS2's `W = I − γhJ`), in place of
//! `dim` differenced right-hand sides:
//! ```text
//! ∂f/∂y = ∂f/∂y|_L  +  ∂f/∂L · Σ_j ∂L_j/∂(G_j, V_j, τ_j) · ∂(G_j, V_j, τ_j)/∂y
//! ```
//! - `∂f/∂y|_L`, the plant at fixed wheel loads: the generator's exact
//!   Jacobian ([`Plant::jacobian`]);
//! - `∂L_j/∂(G_j, V_j, τ_j)`, each wheel's load against its centre, velocity
//!   and torque: dual numbers through the run's own wheel law
//!   ([`rover_dynamics::wheel_ground::load_derivative`]), with the contact
//!   patches' frames held;
//! - `∂V_j/∂w = J_j(x)`: exact, the wheel velocities being linear in `w`
//!   (the plant's kinematics at unit `w`); `∂G_j/∂x = J_j·B⁻¹`, since
//!   `Ġ_j = J_j·w` and `ẋ = B·w`, with `B⁻¹ = blockdiag(Rᵀ, E, I)` in
//!   closed form (MODEL.md §2);
//! - `∂f/∂L`: exact, `ẇ` being linear in the loads (one plant evaluation per
//!   column, no difference quotient);
//! - `∂τ/∂y` and the controller's integral rates `∂ζ̇/∂y`: differences of the
//!   controller alone (no contact search, no plant);
//! - on a soil, the spins' rows `∂ω̇_j/∂y = (∂τ_j/∂y − ∂T_j/∂y)/I_w`, the
//!   soil's torque T_j differentiated with the load (its last row), and the
//!   loads' dependence on the spins (their last column).
//!
//! Left out are the terms that turn with the geometry — the patch frames,
//! `∂V_j/∂x` at fixed `w`, the steering's dependence on the state — of order
//! F/R and V·C against the tyre's k_w and the cornering law's lateral damping,
//! which make the system stiff. Neither method needs more: BDF's Newton
//! iteration converges to the same solution with any good approximation of
//! `J`, and ROS2 keeps its order with any `W`. The cost is one right-hand side,
//! 2N + dim plant-sized calls and a few µs of per-wheel algebra, against `dim`
//! right-hand sides for differences.

use rover_dynamics::HeightField;
use rover_dynamics::attitude::Attitude;
use rover_dynamics::plant::MIN_COS_ROLL;
use rover_dynamics::plant::{Plant, WheelLoad, WheelState};
use rover_dynamics::wheel_ground::LoadDerivative;

use crate::sim::SimError;

use super::RoverSystem;

/// Buffers of the assembled Jacobian, sized once with the system.
#[derive(Clone, Debug, Default)]
pub(super) struct JacobianWork {
    /// The plant has an exact Jacobian.
    available: bool,
    f0: Vec<f64>,
    plant: Vec<f64>,
    unit: Vec<f64>,
    kinematics: Vec<WheelState>,
    /// `∂V_k/∂w_j` at `[k·n + j]`.
    velocity: Vec<[f64; 3]>,
    /// `∂G_k/∂x_j` at `[k·n + j]`.
    centre: Vec<[f64; 3]>,
    loads: Vec<LoadDerivative>,
    /// `∂τ_k/∂y_j` at `[k·dim + j]`.
    torque: Vec<f64>,
    tau: Vec<f64>,
    /// The wheels' spin rates at a perturbed state, for the motor lines.
    motor_rates: Vec<f64>,
    /// The wheels' slips at a perturbed state, for an anti-spin distribution.
    slips: Vec<f64>,
    y: Vec<f64>,
    zd: Vec<f64>,
    perturbed: Vec<WheelLoad>,
    xd: Vec<f64>,
    wd: Vec<f64>,
}

impl JacobianWork {
    /// Buffers for `n` coordinates, `k` wheels and state dimension `dim`,
    /// and whether `plant` has an exact Jacobian (asked once, at rest).
    pub(super) fn new(plant: &mut impl Plant, n: usize, k: usize, dim: usize) -> Self {
        let mut plant_jacobian = vec![0.0; 4 * n * n];
        let available = plant
            .jacobian(
                &vec![0.0; n],
                &vec![0.0; n],
                &vec![WheelLoad::default(); k],
                &mut plant_jacobian,
            )
            .is_some();
        Self {
            available,
            f0: vec![0.0; dim],
            plant: plant_jacobian,
            unit: vec![0.0; n],
            kinematics: vec![WheelState::default(); k],
            velocity: vec![[0.0; 3]; k * n],
            centre: vec![[0.0; 3]; k * n],
            loads: vec![[[0.0; 8]; 10]; k],
            torque: vec![0.0; k * dim],
            tau: vec![0.0; k],
            motor_rates: vec![0.0; k],
            slips: vec![0.0; k],
            y: vec![0.0; dim],
            zd: vec![0.0; dim - 2 * n],
            perturbed: vec![WheelLoad::default(); k],
            xd: vec![0.0; n],
            wd: vec![0.0; n],
        }
    }
}

/// `E` of `Ω = E·[φ̇, θ̇, ψ̇]` (MODEL.md §2, eq. 9): the inverse of the
/// angle rates' `E⁻¹` ([`Attitude::rates`]), B's attitude block.
fn euler_rate_matrix(a: &Attitude<f64>) -> [[f64; 3]; 3] {
    [
        [a.cth, 0.0, -a.sth * a.cphi],
        [0.0, 1.0, a.sphi],
        [a.sth, 0.0, a.cth * a.cphi],
    ]
}

/// The difference step for coordinate value `v` (Hairer & Wanner II, §IV.8).
fn step(v: f64) -> f64 {
    let perturbed = v + f64::EPSILON.sqrt() * v.abs().max(1.0);
    perturbed - v
}

/// The controller's view of a state: `(x, w, z, ω)`, z its integral
/// states and ω the wheels' spins (the last `spins` states).
type Parts<'a> = (&'a [f64], &'a [f64], &'a [f64], &'a [f64]);

/// Calls `f(j, h, parts)` at `y + h·e_j` for every state j, `h` the
/// difference step: forward differences of what is cheap to evaluate (the
/// controller), `scratch` holding the perturbed state.
fn each_perturbed(
    y: &[f64],
    (n, spins): (usize, usize),
    scratch: &mut [f64],
    mut f: impl FnMut(usize, f64, Parts<'_>),
) {
    scratch.copy_from_slice(y);
    for j in 0..y.len() {
        let h = step(y[j]);
        scratch[j] = y[j] + h;
        let (x, rest) = scratch.split_at(n);
        let (w, rest) = rest.split_at(n);
        let (z, spin) = rest.split_at(rest.len() - spins);
        f(j, h, (x, w, z, spin));
        scratch[j] = y[j];
    }
}

impl<P: Plant, H: HeightField> RoverSystem<P, H> {
    /// Writes the assembled `∂f/∂y` at `(t, y)` into `jac` (row-major) and
    /// returns the right-hand sides it spent; `None` when the plant has no
    /// exact Jacobian or the attitude is singular there, and the integrator
    /// differences the right-hand side instead.
    pub(super) fn assembled_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        jac: &mut [f64],
    ) -> Option<Result<usize, SimError>> {
        if !self.jacobian_work.available {
            return None;
        }
        let mut work = std::mem::take(&mut self.jacobian_work);
        let result = self.assemble(t, y, jac, &mut work);
        self.jacobian_work = work;
        result
    }

    /// The right-hand side `dy = f(t, y)` and its Jacobian `jac = ∂f/∂y`
    /// (row-major) from one evaluation, for an observer linearizing about
    /// its estimate: the assembled Jacobian when the plant has an exact
    /// one ([`OdeSystem::jacobian`](rover_integrate::OdeSystem::jacobian)),
    /// else (the generic plant, or a singular attitude) forward
    /// differences of the whole right-hand side, as the integrators take
    /// them then. Allocates nothing.
    pub fn rhs_and_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        jac: &mut [f64],
    ) -> Result<(), SimError> {
        if let Some(result) = self.assembled_jacobian(t, y, jac) {
            result?;
            dy.copy_from_slice(&self.jacobian_work.f0[..dy.len()]);
            return Ok(());
        }
        self.differenced_jacobian(t, y, dy, jac)
    }

    /// `dy = f(t, y)` and `jac` by forward differences of `f`.
    fn differenced_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        dy: &mut [f64],
        jac: &mut [f64],
    ) -> Result<(), SimError> {
        let dim = y.len();
        self.evaluate(t, y, dy)?;
        let mut work = std::mem::take(&mut self.jacobian_work);
        let mut result = Ok(());
        work.y.copy_from_slice(y);
        for j in 0..dim {
            let h = step(y[j]);
            work.y[j] = y[j] + h;
            result = self.evaluate(t, &work.y, &mut work.f0);
            work.y[j] = y[j];
            if result.is_err() {
                break;
            }
            for i in 0..dim {
                jac[i * dim + j] = (work.f0[i] - dy[i]) / h;
            }
        }
        self.jacobian_work = work;
        result?;
        // The wheels and reports of the last evaluation are those of `y`.
        self.evaluate(t, y, dy)
    }

    /// Each wheel's spin rate \[rad/s\] at `(t, y)` into `rates`, as
    /// [`RoverSystem::wheel_spin_rates`] gives it, and its gradient
    /// `∂rate_k/∂y` into `gradient[k·dim ..][..dim]`: on a soil the spin
    /// state (a unit gradient); on rigid ground the rolling rate
    /// `heading·V_k / (|heading|·r)`, linear in `w` since `V_k = J_k(x)·w`
    /// (`∂V_k/∂w` from the kinematics at unit pseudo-velocities, exact),
    /// its turn with `x` at fixed `w` (the heading and the lever arms
    /// moving with the attitude and the suspension) left out, as the
    /// assembled Jacobian leaves out `∂V/∂x`. Allocates nothing.
    pub fn wheel_spin_rate_gradients(
        &mut self,
        t: f64,
        y: &[f64],
        rates: &mut [f64],
        gradient: &mut [f64],
    ) {
        let (n, dim) = (self.n, y.len());
        gradient.iter_mut().for_each(|g| *g = 0.0);
        let range = self.spin_range();
        if !range.is_empty() {
            rates.copy_from_slice(&y[range.clone()]);
            for (k, s) in range.enumerate() {
                gradient[k * dim + s] = 1.0;
            }
            return;
        }
        rates.iter_mut().for_each(|r| *r = 0.0);
        if self.ground.is_none() {
            return;
        }
        let t = self.command_time(t);
        let (x, w, z, _) = self.parts(y);
        self.place_wheels(t, x, w, z);
        let work = &mut self.jacobian_work;
        let radii = self.ground.as_ref().map_or(&[][..], |g| g.radii());
        for ((r, s), radius) in rates.iter_mut().zip(&self.wheels).zip(radii) {
            *r = super::rolling_rate(s.spin_axis, s.velocity, *radius);
        }
        for j in 0..n {
            work.unit.iter_mut().for_each(|v| *v = 0.0);
            work.unit[j] = 1.0;
            self.plant
                .wheels(x, &work.unit, &self.steer, &mut work.kinematics);
            for (k, (s, radius)) in work.kinematics.iter().zip(radii).enumerate() {
                // The heading is the spin axis's, which the unit call shares.
                gradient[k * dim + n + j] = super::rolling_rate(s.spin_axis, s.velocity, *radius);
            }
        }
    }

    fn assemble(
        &mut self,
        t: f64,
        y: &[f64],
        jac: &mut [f64],
        work: &mut JacobianWork,
    ) -> Option<Result<usize, SimError>> {
        let (n, k, dim) = (self.n, self.wheels.len(), y.len());
        let two_n = 2 * n;
        // The wheels, contacts, torques and loads at y.
        if let Err(e) = self.evaluate(t, y, &mut work.f0) {
            return Some(Err(e));
        }
        let (x, rest) = y.split_at(n);
        let w = &rest[..n];
        // None is not reached for a plant that had a Jacobian at construction.
        self.plant.jacobian(x, w, &self.loads, &mut work.plant)?;
        jac.iter_mut().for_each(|v| *v = 0.0);
        for i in 0..two_n {
            jac[i * dim..i * dim + two_n].copy_from_slice(&work.plant[i * two_n..(i + 1) * two_n]);
        }
        let Some(ground) = &self.ground else {
            // Free flight: no load depends on the state.
            self.controller_rows(t, y, jac, work);
            return Some(Ok(1));
        };

        // The kinematics at unit pseudo-velocities: J_j's columns.
        for j in 0..n {
            work.unit.iter_mut().for_each(|v| *v = 0.0);
            work.unit[j] = 1.0;
            self.plant
                .wheels(x, &work.unit, &self.steer, &mut work.kinematics);
            for (wheel, s) in work.kinematics.iter().enumerate() {
                work.velocity[wheel * n + j] = s.velocity;
            }
        }
        // ∂G/∂x = J·B⁻¹, B⁻¹ = blockdiag(Rᵀ, E, I) in closed form.
        let att = Attitude::new(x[3], x[4], x[5]);
        if att.cphi.abs() < MIN_COS_ROLL {
            return None;
        }
        let (r, e) = (att.rotation(), euler_rate_matrix(&att));
        for wheel in 0..k {
            let row = &work.velocity[wheel * n..(wheel + 1) * n];
            let centre = &mut work.centre[wheel * n..(wheel + 1) * n];
            for axis in 0..3 {
                for c in 0..3 {
                    centre[c][axis] = (0..3).map(|i| row[i][axis] * r[c][i]).sum();
                    centre[3 + c][axis] = (0..3).map(|i| row[3 + i][axis] * e[i][c]).sum();
                }
            }
            centre[6..].copy_from_slice(&row[6..]);
        }

        // The controller's torques, differenced.
        let tc = self.command_time(t);
        // The wheels' loads are held at the evaluation's (as the loads' own
        // columns hold the contacts); an anti-spin distribution's slips move
        // with the spins and the centres' velocities (the spin is light: its
        // loop through the slip is the stiff one), the contacts held.
        let (control, commands, normals) = (&self.control, &self.torque_commands, &self.normals);
        let reads_slip = control.reads_slip();
        let slips = &mut work.slips;
        let torques = &self.torques;
        let (tau, torque) = (&mut work.tau, &mut work.torque);
        let spins = self.spin_range();
        // The motor lines' spin rates: on a soil the (perturbed) spins; on
        // rigid ground the rolling rates, moved by a pseudo-velocity's
        // perturbation along J_j (the heading's turn with x is left out).
        let curves = control.has_motor_curves();
        let (base, velocity, rates) = (&self.motor_rates, &work.velocity, &mut work.motor_rates);
        let (wheels, radii) = (&self.wheels, control.radii());
        // Without a loop or a motor line the torques are the commands,
        // which no state moves.
        let fixed = self.open_loop && !curves;
        if fixed {
            torque.iter_mut().for_each(|v| *v = 0.0);
        } else {
            each_perturbed(y, (n, spins.len()), &mut work.y, |j, h, parts| {
                let rates: &[f64] = if !curves {
                    &[]
                } else if !parts.3.is_empty() {
                    parts.3
                } else {
                    rates.copy_from_slice(base);
                    if (n..two_n).contains(&j) {
                        for (wheel, r) in rates.iter_mut().enumerate() {
                            let a = wheels[wheel].spin_axis;
                            let dv = velocity[wheel * n + j - n];
                            *r += h * super::rolling_rate(a, dv, radii[wheel]);
                        }
                    }
                    rates
                };
                if reads_slip {
                    for (wheel, slip) in slips.iter_mut().enumerate() {
                        let mut state = wheels[wheel];
                        if (n..two_n).contains(&j) {
                            let dv = velocity[wheel * n + j - n];
                            (0..3).for_each(|a| state.velocity[a] += h * dv[a]);
                        }
                        *slip = ground.slip(wheel, &state, parts.3[wheel]);
                    }
                }
                control.torques(tc, parts, (normals, slips), commands, rates, tau);
                for wheel in 0..k {
                    torque[wheel * dim + j] = (tau[wheel] - torques[wheel]) / h;
                }
            });
        }

        let spin = &y[spins.clone()];
        ground.load_derivatives(&self.wheels, &self.torques, spin, &mut work.loads);

        // Each column through the loads: ẇ is linear in them, so one plant
        // evaluation at L + s·ΔL gives ∂ẇ/∂L·ΔL exactly (s only keeps the
        // sum well scaled).
        let largest_load = self
            .loads
            .iter()
            .flat_map(|l| l.force.iter().chain(&l.moment).chain(&l.stator_torque))
            .fold(0.0f64, |m, v| m.max(v.abs()));
        for j in 0..dim {
            let mut largest = 0.0f64;
            for wheel in 0..k {
                let mut input = [0.0; 8];
                if j < n {
                    input[..3].copy_from_slice(&work.centre[wheel * n + j]);
                } else if j < two_n {
                    input[3..6].copy_from_slice(&work.velocity[wheel * n + j - n]);
                }
                input[6] = work.torque[wheel * dim + j];
                if !spins.is_empty() && j == spins.start + wheel {
                    input[7] = 1.0;
                }
                // ΔL = d·input, over the inputs that move (a column moves
                // either the centre or the velocity).
                let d = &work.loads[wheel];
                let mut delta = [0.0; 10];
                for (c, &v) in input.iter().enumerate() {
                    if v != 0.0 {
                        for (o, row) in delta.iter_mut().zip(d) {
                            *o += row[c] * v;
                        }
                    }
                }
                // The spin's row: ω̇ = (τ − T)/I_w.
                if !spins.is_empty() {
                    let inertia = ground.spin_inertias()[wheel];
                    jac[(spins.start + wheel) * dim + j] = (input[6] - delta[9]) / inertia;
                }
                let delta: [f64; 9] = core::array::from_fn(|r| delta[r]);
                largest = delta.iter().fold(largest, |m, v| m.max(v.abs()));
                let p = &mut work.perturbed[wheel];
                p.force.copy_from_slice(&delta[..3]);
                p.moment.copy_from_slice(&delta[3..6]);
                p.stator_torque.copy_from_slice(&delta[6..]);
            }
            if largest == 0.0 {
                continue;
            }
            let scale = (1.0 + largest_load) / largest;
            for (p, l) in work.perturbed.iter_mut().zip(&self.loads) {
                for axis in 0..3 {
                    p.force[axis] = l.force[axis] + scale * p.force[axis];
                    p.moment[axis] = l.moment[axis] + scale * p.moment[axis];
                    p.stator_torque[axis] = l.stator_torque[axis] + scale * p.stator_torque[axis];
                }
            }
            if let Err(e) =
                self.plant
                    .derivatives(x, w, &work.perturbed, &mut work.xd, &mut work.wd)
            {
                return Some(Err(SimError::Plant(e)));
            }
            for i in 0..n {
                jac[(n + i) * dim + j] += (work.wd[i] - work.f0[n + i]) / scale;
            }
        }
        self.controller_rows(t, y, jac, work);
        Some(Ok(1))
    }

    /// The rows of the controller's integral states, `∂ζ̇/∂y`, differenced.
    fn controller_rows(&self, t: f64, y: &[f64], jac: &mut [f64], work: &mut JacobianWork) {
        let (n, dim, spins) = (self.n, y.len(), self.spins);
        let states = dim - 2 * n - spins;
        if states == 0 {
            return;
        }
        let tc = self.command_time(t);
        let (zd, f0) = (&mut work.zd[..states], &work.f0);
        each_perturbed(y, (n, spins), &mut work.y, |j, h, parts| {
            self.control.integral_rates(tc, parts, zd);
            for i in 0..states {
                jac[(2 * n + i) * dim + j] = (zd[i] - f0[2 * n + i]) / h;
            }
        });
    }
}
