//! Level 4 of MODEL.md §9: the quasi-static model. No inertia, no damping:
//! at each output instant the horizontal motion (X, Y, ψ) is imposed and the
//! static equilibrium of the rest is solved by Newton–Raphson from the
//! previous solution.
//!
//! ```text
//! unknowns  q = [Z, φ, θ, y1 … ym]
//! equations Q_gravity + Q_springs + Q_wheels = 0 along the inertial
//!           vertical force, the moments about the inertial X and Y axes
//!           through G, and the m suspension rows
//! wheels    F_j = (F_nj / n_z)·e_Z at G_j,  F_nj = k_w·Δ_j
//! ```

use rover_dynamics::Model;
use rover_dynamics::attitude::Attitude;
use rover_dynamics::contact::MeridionalContact;
use rover_dynamics::forces::{Load, add_gravity, add_suspension, add_wheel_loads};
use rover_dynamics::height_field::{HeightField, OffMap};
use rover_dynamics::kinematics::{body_kinematics, wheel_kinematics};
use rover_dynamics::workspace::Workspace;

/// Why an equilibrium could not be found.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum QuasiStaticError {
    /// Newton–Raphson did not converge.
    #[error(
        "the quasi-static equilibrium did not converge at X = {x:.3} m, Y = {y:.3} m after {iterations} iterations \
         (residual {residual:.3e} N): the rover may have lost contact or tipped; use a dynamic fidelity level here"
    )]
    NoConvergence {
        /// Imposed X \[m\].
        x: f64,
        /// Imposed Y \[m\].
        y: f64,
        /// Iterations made.
        iterations: usize,
        /// Largest residual left [N or N·m].
        residual: f64,
    },
    /// The equilibrium puts a suspension coordinate beyond its travel: the
    /// rover would rest on a bump stop, where its fitted kinematics do not
    /// reach.
    #[error(
        "at the static equilibrium on flat ground suspension coordinate y{} is {value:.6} \
         (rad, or m for a length), outside its travel [{min:.6}, {max:.6}]: the rover rests on a bump stop; \
         stiffen the spring or move its neutral, or widen the travel (docs/DESCRIPTION.md)",
        coordinate + 1
    )]
    OutsideTravel {
        /// The coordinate (0-based).
        coordinate: usize,
        /// Its value at the equilibrium.
        value: f64,
        /// Its lower travel limit.
        min: f64,
        /// Its upper travel limit.
        max: f64,
    },
    /// A wheel left the terrain map.
    #[error("wheel {} left the terrain: {off}", wheel + 1)]
    OffMap {
        /// Wheel (0-based).
        wheel: usize,
        /// The query.
        off: OffMap,
    },
}

/// The equilibrium solver with its scratch storage.
pub struct QuasiStatic<'a, H> {
    model: &'a Model,
    terrain: &'a H,
    ws: Workspace<f64>,
    search: MeridionalContact,
    neutral: Vec<f64>,
    loads: Vec<Load<f64>>,
    points: Vec<[f64; 3]>,
    // Scratch of a residual evaluation: coordinates, zero rates, Q.
    x: Vec<f64>,
    zeros: Vec<f64>,
    gq: Vec<f64>,
    /// The current solution [Z, φ, θ, y…].
    pub q: Vec<f64>,
    /// Residual evaluations so far.
    pub residual_evals: u64,
    /// Newton iterations so far.
    pub iterations: u64,
}

/// Largest Newton iterations per instant.
const MAX_ITERATIONS: usize = 50;

/// Largest change of any unknown in one Newton step [m or rad].
const MAX_STEP: f64 = 0.1;

impl<'a, H: HeightField> QuasiStatic<'a, H> {
    /// A solver starting from `q0` = [Z, φ, θ, y…].
    /// The first guess is lowered by the static tyre deflection W/Σk_w.
    pub fn new(
        model: &'a Model,
        terrain: &'a H,
        search: MeridionalContact,
        mut q0: Vec<f64>,
    ) -> Self {
        let stiffness: f64 = model.wheels.iter().map(|w| w.stiffness).sum();
        q0[0] -= model.total_mass() * model.gravity / stiffness;
        let zero = Load {
            force: [0.0; 3],
            moment: [0.0; 3],
            stator_torque: [0.0; 3],
        };
        Self {
            model,
            terrain,
            ws: Workspace::new(model),
            search,
            neutral: model.coordinates.iter().map(|c| c.neutral).collect(),
            loads: vec![zero; model.wheels.len()],
            points: vec![[0.0; 3]; model.wheels.len()],
            x: Vec::with_capacity(model.dof()),
            zeros: vec![0.0; model.dof()],
            gq: vec![0.0; model.dof()],
            q: q0,
            residual_evals: 0,
            iterations: 0,
        }
    }

    /// Start the next solve from the attitude of the plane fitted through
    /// the terrain under the wheels at pose (X, Y, ψ), and the height at
    /// which the wheels just touch it, lowered by the static tyre
    /// deflection: on a slope a level start leaves the downhill wheels in
    /// the air, a nearly singular Jacobian from which Newton wanders off.
    /// The suspension coordinates stay. With fewer than three wheels, or
    /// wheels in a line, nothing changes.
    pub fn align(&mut self, pose: [f64; 3]) -> Result<(), QuasiStaticError> {
        let model = self.model;
        let y = self.q[3..].to_vec();
        let (s, c) = pose[2].sin_cos();
        // The wheels' positions in heading axes (level) and the ground there.
        let mut points = Vec::with_capacity(model.wheels.len());
        for (k, w) in model.wheels.iter().enumerate() {
            let u = model.bodies[w.body].position.value(&y);
            let (gx, gy) = (pose[0] + c * u[0] - s * u[1], pose[1] + s * u[0] + c * u[1]);
            let h = self
                .terrain
                .height(gx, gy)
                .map_err(|off| QuasiStaticError::OffMap { wheel: k, off })?;
            points.push((u[0], u[1], h));
        }
        // Least squares h = a + b·x + c·y in heading axes: the normal
        // equations, by Cramer's rule.
        let n = points.len() as f64;
        let sum = |f: &dyn Fn(&(f64, f64, f64)) -> f64| points.iter().map(f).sum::<f64>();
        let (sx, sy, sh) = (sum(&|p| p.0), sum(&|p| p.1), sum(&|p| p.2));
        let (sxx, syy, sxy) = (
            sum(&|p| p.0 * p.0),
            sum(&|p| p.1 * p.1),
            sum(&|p| p.0 * p.1),
        );
        let (sxh, syh) = (sum(&|p| p.0 * p.2), sum(&|p| p.1 * p.2));
        let det3 = |m: [[f64; 3]; 3]| {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        };
        let m = [[n, sx, sy], [sx, sxx, sxy], [sy, sxy, syy]];
        let d = det3(m);
        if points.len() < 3 || d.is_nan() || d.abs() <= 1e-12 * (1.0 + n * n) {
            return Ok(());
        }
        let rhs = [sh, sxh, syh];
        let with = |col: usize| {
            let mut a = m;
            for r in 0..3 {
                a[r][col] = rhs[r];
            }
            det3(a)
        };
        let (forward, left) = (with(1) / d, with(2) / d);
        // Nose up on a rise ahead is a negative pitch (θ turns x towards −z);
        // left side up on a rise to the left is a positive roll.
        let (theta, phi) = (-forward.atan(), left.atan());
        let z = crate::ground::touchdown_heights(
            model,
            [pose[0], pose[1]],
            Attitude::new(phi, theta, pose[2]),
            &y,
            self.terrain,
        )
        .map_err(|e| QuasiStaticError::OffMap {
            wheel: e.wheel,
            off: e.off,
        })?
        .into_iter()
        .fold(f64::NEG_INFINITY, f64::max);
        let stiffness: f64 = model.wheels.iter().map(|w| w.stiffness).sum();
        self.q[0] = z - model.total_mass() * model.gravity / stiffness;
        self.q[1] = phi;
        self.q[2] = theta;
        Ok(())
    }

    /// The full coordinates x for a pose (X, Y, ψ) and unknowns q.
    pub fn coordinates(&self, pose: [f64; 3], q: &[f64]) -> Vec<f64> {
        let mut x = vec![pose[0], pose[1], q[0], q[1], q[2], pose[2]];
        x.extend_from_slice(&q[3..]);
        x
    }

    /// Each wheel's contact point H (of its most loaded patch; below the
    /// centre by the radius when airborne) at the last evaluation
    /// ([`QuasiStatic::normal_forces`] makes one at the solution).
    pub fn contact_points(&self) -> &[[f64; 3]] {
        &self.points
    }

    /// Vertical force on each wheel at the current solution, for a pose.
    pub fn normal_forces(
        &mut self,
        pose: [f64; 3],
        out: &mut [f64],
    ) -> Result<(), QuasiStaticError> {
        let q = self.q.clone();
        let mut r = vec![0.0; q.len()];
        self.residual(pose, &q, &mut r)?;
        for (o, l) in out.iter_mut().zip(&self.loads) {
            *o = l.force[2];
        }
        Ok(())
    }

    /// Equilibrium residual at pose (X, Y, ψ) and unknowns q.
    fn residual(
        &mut self,
        pose: [f64; 3],
        q: &[f64],
        r: &mut [f64],
    ) -> Result<(), QuasiStaticError> {
        self.residual_evals += 1;
        let model = self.model;
        let mut x = core::mem::take(&mut self.x);
        x.clear();
        x.extend_from_slice(&[pose[0], pose[1], q[0], q[1], q[2], pose[2]]);
        x.extend_from_slice(&q[3..]);
        let zeros = &self.zeros;
        body_kinematics(model, &x[6..], &mut self.ws);
        let att = Attitude::new(x[3], x[4], x[5]);
        for (k, wheel) in model.wheels.iter().enumerate() {
            let wk = wheel_kinematics(model, &self.ws, &att, &x, zeros, k, 0.0);
            let contact = self
                .search
                .find(self.terrain, wk.centre, wk.spin_axis, wheel.radius)
                .map_err(|off| QuasiStaticError::OffMap { wheel: k, off })?;
            // Each patch's vertical force acts at its contact point H, as
            // the dynamic law's forces do (MODEL.md §7): reduced to the
            // wheel centre it is the force and the moment (H − G_j) × F on
            // the carrier, less its axial part, which the motor holds (the
            // stator takes it). Applied at the centre instead, a slope would
            // move the support polygon uphill by R·sin α and a cambered
            // wheel its load sideways.
            let (mut force, mut moment, mut stator) = ([0.0; 3], [0.0; 3], [0.0; 3]);
            let a = wk.spin_axis;
            let (mut strongest, mut point) = (
                0.0,
                [wk.centre[0], wk.centre[1], wk.centre[2] - wheel.radius],
            );
            for p in contact.patches() {
                let fn_ = (wheel.stiffness * p.deflection).max(0.0);
                let fz = fn_ / p.normal[2].max(1e-6);
                if fz > strongest {
                    (strongest, point) = (fz, p.point);
                }
                let arm = [0, 1, 2].map(|i| p.point[i] - wk.centre[i]);
                // (H − G_j) × (0, 0, F_z).
                let m = [arm[1] * fz, -arm[0] * fz, 0.0];
                let axial = m[0] * a[0] + m[1] * a[1] + m[2] * a[2];
                force[2] += fz;
                for i in 0..3 {
                    moment[i] += m[i] - axial * a[i];
                    stator[i] += axial * a[i];
                }
            }
            self.points[k] = point;
            self.loads[k].force = force;
            self.loads[k].moment = moment;
            self.loads[k].stator_torque = stator;
        }
        let gq = &mut self.gq;
        gq.iter_mut().for_each(|v| *v = 0.0);
        add_gravity(model, &self.ws, &att, gq);
        add_suspension(model, &self.neutral, &x[6..], &zeros[6..], gq);
        add_wheel_loads(model, &self.ws, &att, &self.loads, gq);
        let rot = att.rotation();
        let world =
            |v: [f64; 3]| [0, 1, 2].map(|i| rot[i][0] * v[0] + rot[i][1] * v[1] + rot[i][2] * v[2]);
        let f = world([gq[0], gq[1], gq[2]]);
        let m = world([gq[3], gq[4], gq[5]]);
        r[0] = f[2];
        r[1] = m[0];
        r[2] = m[1];
        r[3..].copy_from_slice(&gq[6..]);
        self.x = x;
        Ok(())
    }

    /// Solve the equilibrium at pose (X, Y, ψ) from the previous solution;
    /// returns the iterations used.
    pub fn solve(&mut self, pose: [f64; 3]) -> Result<usize, QuasiStaticError> {
        let k = self.q.len();
        let weight = self.model.total_mass() * self.model.gravity;
        let tol = 1e-9 * weight.max(1e-12);
        let mut r = vec![0.0; k];
        let mut trial = vec![0.0; k];
        let mut r_trial = vec![0.0; k];
        let mut jac = vec![0.0; k * k];
        let mut q = self.q.clone();
        self.residual(pose, &q, &mut r)?;
        let norm = |v: &[f64]| v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        for it in 0..MAX_ITERATIONS {
            if norm(&r) <= tol {
                self.q = q;
                self.iterations += it as u64;
                return Ok(it);
            }
            // Forward-difference Jacobian.
            for c in 0..k {
                let h = 1e-7 * (1.0 + q[c].abs());
                trial.copy_from_slice(&q);
                trial[c] += h;
                self.residual(pose, &trial, &mut r_trial)?;
                for row in 0..k {
                    jac[row * k + c] = (r_trial[row] - r[row]) / h;
                }
            }
            let mut step: Vec<f64> = r.iter().map(|v| -v).collect();
            if !gauss_solve(&mut jac, &mut step, k) {
                // No wheel in contact (a singular Jacobian): lower the rover
                // by a millimetre and try again.
                q[0] -= 1e-3;
                self.residual(pose, &q, &mut r)?;
                continue;
            }
            // A step no larger than a trust radius: where a wheel is off the
            // ground the Jacobian is nearly singular (a rover started level
            // on a slope has its downhill wheels in the air) and the Newton
            // step can be tens of radians; a bounded step lets the wheels
            // touch first.
            let longest = step.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if longest > MAX_STEP {
                let shrink = MAX_STEP / longest;
                step.iter_mut().for_each(|v| *v *= shrink);
            }
            // Backtracking (Armijo) on ½|r|².
            let sq = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>();
            let base = sq(&r);
            let mut lambda = 1.0;
            loop {
                for i in 0..k {
                    trial[i] = q[i] + lambda * step[i];
                }
                self.residual(pose, &trial, &mut r_trial)?;
                if sq(&r_trial) <= (1.0 - 1e-4 * lambda) * base || lambda < 1e-3 {
                    break;
                }
                lambda *= 0.5;
            }
            q.copy_from_slice(&trial);
            r.copy_from_slice(&r_trial);
        }
        if norm(&r) <= tol {
            self.q = q;
            return Ok(MAX_ITERATIONS);
        }
        Err(QuasiStaticError::NoConvergence {
            x: pose[0],
            y: pose[1],
            iterations: MAX_ITERATIONS,
            residual: norm(&r),
        })
    }
}

/// Gaussian elimination with partial pivoting; false if singular.
fn gauss_solve(a: &mut [f64], b: &mut [f64], n: usize) -> bool {
    for c in 0..n {
        let p = (c..n)
            .max_by(|&i, &j| a[i * n + c].abs().total_cmp(&a[j * n + c].abs()))
            .unwrap_or(c);
        if a[p * n + c].abs() < 1e-300 || !a[p * n + c].is_finite() {
            return false;
        }
        if p != c {
            for k in 0..n {
                a.swap(c * n + k, p * n + k);
            }
            b.swap(c, p);
        }
        for r in c + 1..n {
            let f = a[r * n + c] / a[c * n + c];
            for k in c..n {
                a[r * n + k] -= f * a[c * n + k];
            }
            b[r] -= f * b[c];
        }
    }
    for c in (0..n).rev() {
        let s: f64 = (c + 1..n).map(|k| a[c * n + k] * b[k]).sum();
        b[c] = (b[c] - s) / a[c * n + c];
    }
    true
}

/// The suspension coordinates of the rover's static equilibrium on flat
/// ground, level and at rest: the configuration the reduced fidelity levels
/// freeze at (a loaded rover moves about it, not about its unloaded rest).
///
/// Rounded to [`EQUILIBRIUM_GRID`]: the solve converges to the contact
/// search's own tolerance, and a change of 2e-11 rad in its last digits
/// (from a different crossing refinement, say) rewrote every constant of a
/// checked-in reduced plant. On the grid such noise changes nothing, unless
/// a coordinate sits within the noise of a grid midpoint.
pub fn flat_ground_equilibrium(model: &Model) -> Result<Vec<f64>, QuasiStaticError> {
    let y = flat_ground_solution(model)?.coordinates;
    within_travel(model, &y)?;
    Ok(y.into_iter()
        .map(|v| (v / EQUILIBRIUM_GRID).round() * EQUILIBRIUM_GRID)
        .collect())
}

/// Step of the grid the frozen equilibrium is rounded to \[rad or m\]:
/// far below any physical effect, far above the solver's noise.
pub const EQUILIBRIUM_GRID: f64 = 1e-9;

/// Each wheel's vertical load \[N\] in the static equilibrium on flat ground
/// (the weights of a torque distribution "by static load", MODEL.md §8).
pub fn flat_ground_loads(model: &Model) -> Result<Vec<f64>, QuasiStaticError> {
    Ok(flat_ground_solution(model)?.loads)
}

/// The full coordinates x = [X, Y, Z, φ, θ, ψ, y…] of the static
/// equilibrium on flat ground at X = Y = ψ = 0, to the solver's own
/// tolerance (not rounded as [`flat_ground_equilibrium`] is): the point a
/// linearization is taken about.
pub fn flat_ground_pose(model: &Model) -> Result<Vec<f64>, QuasiStaticError> {
    let solution = flat_ground_solution(model)?;
    within_travel(model, &solution.coordinates)?;
    Ok(solution.pose)
}

/// Each coordinate of an equilibrium `y` inside its travel (to the
/// tolerance of the grid the equilibrium is rounded to).
fn within_travel(model: &Model, y: &[f64]) -> Result<(), QuasiStaticError> {
    for (i, (c, &v)) in model.coordinates.iter().zip(y).enumerate() {
        if !(v >= c.min - EQUILIBRIUM_GRID && v <= c.max + EQUILIBRIUM_GRID) {
            return Err(QuasiStaticError::OutsideTravel {
                coordinate: i,
                value: v,
                min: c.min,
                max: c.max,
            });
        }
    }
    Ok(())
}

/// The static equilibrium on flat ground.
struct FlatGround {
    /// Suspension coordinates y.
    coordinates: Vec<f64>,
    /// Each wheel's normal load \[N\].
    loads: Vec<f64>,
    /// Full coordinates x at X = Y = ψ = 0.
    pose: Vec<f64>,
}

/// Solve the static equilibrium on flat ground.
fn flat_ground_solution(model: &Model) -> Result<FlatGround, QuasiStaticError> {
    let flat = rover_terrain::Terrain::default();
    let mut q0 = vec![model.touchdown_height(), 0.0, 0.0];
    q0.extend_from_slice(&model.rest());
    let mut solver = QuasiStatic::new(model, &flat, MeridionalContact::default(), q0);
    solver.solve([0.0; 3])?;
    let mut loads = vec![0.0; model.wheels.len()];
    solver.normal_forces([0.0; 3], &mut loads)?;
    Ok(FlatGround {
        coordinates: solver.q[3..].to_vec(),
        loads,
        pose: solver.coordinates([0.0; 3], &solver.q),
    })
}
