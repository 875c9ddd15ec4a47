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
    /// No equilibrium exists near the imposed pose: the vertical wheel
    /// forces, which can only push, balance gravity's moment only when the
    /// centre of mass's vertical projection lies inside the support polygon
    /// (the convex hull of the loaded contact points), and it lies outside.
    #[error("{0}")]
    Tips(Box<Tipping>),
    /// No wheel touches the ground anywhere Newton–Raphson looked.
    #[error(
        "no quasi-static equilibrium at X = {x:.3} m, Y = {y:.3} m: no wheel reaches the ground; \
         use a dynamic fidelity level here"
    )]
    NoContact {
        /// Imposed X \[m\].
        x: f64,
        /// Imposed Y \[m\].
        y: f64,
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

/// Where the rover would tip (see [`QuasiStaticError::Tips`]).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}", tip_message(*x, *y, edge, *outside, touching, on_stops))]
pub struct Tipping {
    /// Imposed X \[m\].
    pub x: f64,
    /// Imposed Y \[m\].
    pub y: f64,
    /// The wheels (0-based) of the support polygon's edge (or corner)
    /// the centre of mass lies beyond.
    pub edge: Vec<usize>,
    /// Horizontal distance of the centre of mass beyond that edge \[m\].
    pub outside: f64,
    /// The wheels (0-based) on the ground.
    pub touching: Vec<usize>,
    /// Suspension coordinates (0-based) beyond their travel, on a bump
    /// stop.
    pub on_stops: Vec<usize>,
}

/// The tipping error's text: beyond an edge by a distance, or (within
/// 1 mm) on the line of the only wheels on the ground, a balance that
/// tips either way.
fn tip_message(
    x: f64,
    y: f64,
    edge: &[usize],
    outside: f64,
    touching: &[usize],
    on_stops: &[usize],
) -> String {
    let why = if outside < 1e-3 && edge.len() < 3 && touching.len() < 3 {
        format!(
            "the rover would tip: its centre of mass lies on the line of {}, the only wheels on the ground, a balance it falls out of",
            wheel_list(touching)
        )
    } else {
        format!(
            "the rover would tip about {}: its centre of mass is {outside:.3} m outside the support polygon of the wheels on the ground ({})",
            wheel_list(edge),
            wheel_list(touching)
        )
    };
    format!(
        "no quasi-static equilibrium at X = {x:.3} m, Y = {y:.3} m: {why}{}; use a dynamic fidelity level here",
        stops_note(on_stops)
    )
}

/// The scratch of one solve: residuals, trial point and its residuals,
/// Jacobian, step, iterate and best iterate, taken out of the solver while
/// it evaluates residuals.
#[derive(Default)]
struct Scratch {
    r: Vec<f64>,
    trial: Vec<f64>,
    r_trial: Vec<f64>,
    jac: Vec<f64>,
    step: Vec<f64>,
    q: Vec<f64>,
    best: Vec<f64>,
}

impl Scratch {
    fn new(k: usize) -> Self {
        Self {
            r: vec![0.0; k],
            trial: vec![0.0; k],
            r_trial: vec![0.0; k],
            jac: vec![0.0; k * k],
            step: vec![0.0; k],
            q: vec![0.0; k],
            best: vec![0.0; k],
        }
    }
}

/// The largest magnitude of `v` (the residual norm the solves judge by).
fn max_abs(v: &[f64]) -> f64 {
    v.iter().fold(0.0f64, |a, b| a.max(b.abs()))
}

/// Shorten `step` to the trust radius [`MAX_STEP`]: where a wheel is off
/// the ground the Jacobian is nearly singular and a raw step can be tens
/// of radians.
fn limit_step(step: &mut [f64]) {
    let longest = max_abs(step);
    if longest > MAX_STEP {
        let shrink = MAX_STEP / longest;
        step.iter_mut().for_each(|v| *v *= shrink);
    }
}

/// "wheel 3", "wheels 1 and 3", "wheels 1, 2 and 4" (1-based).
fn wheel_list(w: &[usize]) -> String {
    let n: Vec<String> = w.iter().map(|k| (k + 1).to_string()).collect();
    match n.len() {
        0 => "no wheel".into(),
        1 => format!("wheel {}", n[0]),
        k => format!("wheels {} and {}", n[..k - 1].join(", "), n[k - 1]),
    }
}

/// ", suspension coordinates y2 on their bump stops" or nothing.
fn stops_note(c: &[usize]) -> String {
    if c.is_empty() {
        return String::new();
    }
    let n: Vec<String> = c.iter().map(|k| format!("y{}", k + 1)).collect();
    format!(", suspension coordinate(s) {} on a bump stop", n.join(", "))
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
    scratch: Scratch,
    r_check: Vec<f64>,
    /// The last differenced Jacobian, reused by the next solves (a chord
    /// method) while its steps converge fast; `kept_valid` once there is one.
    kept_jac: Vec<f64>,
    kept_valid: bool,
    /// The pose of the current solution, once one was solved.
    solved_at: Option<[f64; 3]>,
    /// Accept an equilibrium balanced on fewer than three wheels (or with
    /// the centre of mass on the support polygon's edge): the rest pose
    /// that linearization and the reduced levels are taken about, which
    /// may be a balance (a rover on one axle), not a path to follow.
    pub accept_balance: bool,
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

/// Smallest fraction of the way from the last solved pose to the next that
/// the continuation steps by before it gives up.
const MIN_FRACTION: f64 = 1.0 / 64.0;

/// Largest pseudo-transient iterations per instant.
const PSEUDO_TRANSIENT_ITERATIONS: usize = 400;

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
            scratch: Scratch::new(q0.len()),
            r_check: vec![0.0; q0.len()],
            kept_jac: vec![0.0; q0.len() * q0.len()],
            kept_valid: false,
            solved_at: None,
            accept_balance: false,
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
    /// returns the Newton iterations used.
    ///
    /// When Newton–Raphson does not converge from the previous solution (a
    /// wheel whose ground fell away by more than its static deflection since
    /// the last pose starts in the air, where the Jacobian does not see the
    /// ground and is nearly singular), the pose is approached by
    /// continuation: from the last solved pose in steps halved on each
    /// failure, down to 1/64 of the way. Where even that fails,
    /// the error says why: the rover would tip (the centre of mass outside
    /// the support polygon), no wheel reaches the ground, or (neither)
    /// Newton–Raphson did not converge.
    pub fn solve(&mut self, pose: [f64; 3]) -> Result<usize, QuasiStaticError> {
        let first = match self.newton(pose)? {
            Ok(it) => {
                self.solved_at = Some(pose);
                return Ok(it);
            }
            Err(residual) => residual,
        };
        let mut total = MAX_ITERATIONS;
        let (at, residual) = match self.solved_at {
            Some(from) => match self.continuation(from, pose, &mut total)? {
                Ok(()) => {
                    self.solved_at = Some(pose);
                    return Ok(total);
                }
                Err(failed) => failed,
            },
            None => (pose, first),
        };
        // The branch followed ends in a fold (a rover balanced on three
        // wheels of four, or rocking on a diagonal, whose equilibrium turns
        // unstable), or the start is far from any equilibrium: the rover
        // snaps to another equilibrium, which a damped flow towards a
        // stable one finds from the last solution.
        let diagnosis = self.diagnose(at, total, residual);
        let it = self.pseudo_transient(pose)?;
        total += it.unwrap_or(PSEUDO_TRANSIENT_ITERATIONS);
        if it.is_ok() {
            self.solved_at = Some(pose);
            return Ok(total);
        }
        Err(diagnosis)
    }

    /// Pseudo-transient continuation at `pose` from the current solution:
    /// the steps `(D/Δτ − J)·Δq = r`, with D the magnitudes of the
    /// Jacobian's diagonal, follow the damped flow `D·q̇ = Q(q)` towards a
    /// stable equilibrium while Δτ is small and become Newton's as the
    /// residual falls and Δτ grows (switched evolution relaxation:
    /// Δτ ← Δτ·|r_old|/|r_new|). `Ok(Ok(iterations))` with `q` updated, or
    /// `Ok(Err(residual))` with `q` unchanged.
    fn pseudo_transient(&mut self, pose: [f64; 3]) -> Result<Result<usize, f64>, QuasiStaticError> {
        let k = self.q.len();
        let tol = self.tolerance();
        let mut scratch = core::mem::take(&mut self.scratch);
        let Scratch {
            r,
            trial,
            r_trial,
            jac,
            step,
            q,
            ..
        } = &mut scratch;
        let norm = max_abs;
        let mut out = Ok(Err(f64::INFINITY));
        q.copy_from_slice(&self.q);
        let mut dtau = 1e-2;
        match self.residual(pose, q, r) {
            Err(e) => out = Err(e),
            Ok(()) => {
                for it in 0..PSEUDO_TRANSIENT_ITERATIONS {
                    let now = norm(r);
                    out = Ok(Err(now));
                    if now <= tol {
                        match self.stands(pose, q) {
                            Ok(true) => {}
                            Ok(false) => break,
                            Err(e) => {
                                out = Err(e);
                                break;
                            }
                        }
                        out = Ok(Ok(it));
                        break;
                    }
                    if let Err(e) = self.difference_jacobian(pose, q, r, trial, r_trial, jac) {
                        out = Err(e);
                        break;
                    }
                    for i in 0..k {
                        let d = jac[i * k + i].abs().max(1e-6);
                        for c in 0..k {
                            jac[i * k + c] = -jac[i * k + c];
                        }
                        jac[i * k + i] += d / dtau;
                        step[i] = r[i];
                    }
                    if !gauss_solve(jac, step, k) {
                        dtau *= 0.1;
                        continue;
                    }
                    limit_step(step);
                    for i in 0..k {
                        trial[i] = q[i] + step[i];
                    }
                    if let Err(e) = self.residual(pose, trial, r_trial) {
                        out = Err(e);
                        break;
                    }
                    let next = norm(r_trial);
                    // A step that more than doubles the residual is retaken
                    // shorter; one that lowers it lengthens the next; the
                    // flow may climb a little on its way to a stable
                    // equilibrium.
                    if next.is_nan() || next > 2.0 * now {
                        dtau *= 0.25;
                        continue;
                    }
                    if next < now {
                        dtau = (2.0 * dtau).min(1e12);
                    }
                    q.copy_from_slice(trial);
                    r.copy_from_slice(r_trial);
                }
                if let Ok(Err(_)) = out
                    && norm(r) <= tol
                    && matches!(self.stands(pose, q), Ok(true))
                {
                    out = Ok(Ok(PSEUDO_TRANSIENT_ITERATIONS));
                }
            }
        }
        match out {
            Ok(Ok(it)) => {
                self.q.copy_from_slice(q);
                self.iterations += it as u64;
            }
            _ => self.iterations += PSEUDO_TRANSIENT_ITERATIONS as u64,
        }
        self.scratch = scratch;
        out
    }

    /// Continuation from the solution at `from` to `to` in steps halved on
    /// each failure: `Ok(Err((pose, residual)))` where the step fell below
    /// [`MIN_FRACTION`] of the way, with `q` the last solution reached.
    #[allow(clippy::type_complexity)]
    fn continuation(
        &mut self,
        from: [f64; 3],
        pose: [f64; 3],
        total: &mut usize,
    ) -> Result<Result<(), ([f64; 3], f64)>, QuasiStaticError> {
        let (mut done, mut h) = (0.0f64, 0.5f64);
        while done < 1.0 {
            let next = (done + h).min(1.0);
            let target = [0, 1, 2].map(|i| from[i] + next * (pose[i] - from[i]));
            match self.newton(target)? {
                Ok(it) => {
                    *total += it;
                    done = next;
                    h = (2.0 * h).min(0.5);
                }
                Err(residual) => {
                    *total += MAX_ITERATIONS;
                    h *= 0.5;
                    if h < MIN_FRACTION {
                        return Ok(Err((target, residual)));
                    }
                }
            }
        }
        Ok(Ok(()))
    }

    /// Newton–Raphson at `pose` from the current solution: `Ok(Ok(iterations))`
    /// with `q` updated, or `Ok(Err(residual))` with `q` unchanged and the
    /// iterate of least residual in `best`.
    fn newton(&mut self, pose: [f64; 3]) -> Result<Result<usize, f64>, QuasiStaticError> {
        let mut scratch = core::mem::take(&mut self.scratch);
        let out = self.iterate(pose, &mut scratch);
        if let Ok(Ok(it)) = out {
            self.q.copy_from_slice(&scratch.q);
            self.iterations += it as u64;
        } else {
            self.iterations += MAX_ITERATIONS as u64;
        }
        self.scratch = scratch;
        out
    }

    /// The iterations of [`QuasiStatic::newton`], on taken-out scratch.
    fn iterate(
        &mut self,
        pose: [f64; 3],
        scratch: &mut Scratch,
    ) -> Result<Result<usize, f64>, QuasiStaticError> {
        let Scratch {
            r,
            trial,
            r_trial,
            jac,
            step,
            q,
            best,
        } = scratch;
        let k = self.q.len();
        let tol = self.tolerance();
        q.copy_from_slice(&self.q);
        self.residual(pose, q, r)?;
        let norm = max_abs;
        let sq = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>();
        best.copy_from_slice(q);
        let mut least = norm(r);
        // Between output instants the rover moves a few millimetres and its
        // Jacobian hardly changes: the last differenced one is reused (a
        // chord step costs one residual against k + 1 for a fresh
        // Jacobian) for as long as each step at least halves the residual.
        let mut stale = self.kept_valid;
        for it in 0..MAX_ITERATIONS {
            let now = norm(r);
            if now <= tol {
                // An unstable equilibrium (a rover balanced on a diagonal
                // or on one wheel) is not where it stays.
                if !self.stands(pose, q)? {
                    return Ok(Err(now));
                }
                return Ok(Ok(it));
            }
            if now < least {
                least = now;
                best.copy_from_slice(q);
            }
            if stale {
                jac.copy_from_slice(&self.kept_jac);
            } else {
                self.difference_jacobian(pose, q, r, trial, r_trial, jac)?;
                self.kept_jac.copy_from_slice(jac);
                self.kept_valid = true;
            }
            for (s, v) in step.iter_mut().zip(r.iter()) {
                *s = -v;
            }
            if !gauss_solve(jac, step, k) {
                if stale {
                    stale = false;
                    continue;
                }
                // No wheel in contact (a singular Jacobian): lower the rover
                // by a millimetre and try again.
                q[0] -= 1e-3;
                self.residual(pose, q, r)?;
                continue;
            }
            // A rover started level on a slope has its downhill wheels in the
            // air: a bounded step lets them touch first.
            limit_step(step);
            let base = sq(r);
            if stale {
                // A chord step is kept only if it halves the residual;
                // otherwise the Jacobian is differenced afresh.
                for i in 0..k {
                    trial[i] = q[i] + step[i];
                }
                self.residual(pose, trial, r_trial)?;
                if sq(r_trial) <= 0.25 * base {
                    q.copy_from_slice(trial);
                    r.copy_from_slice(r_trial);
                } else {
                    stale = false;
                }
                continue;
            }
            // Backtracking (Armijo) on ½|r|².
            let mut lambda = 1.0;
            loop {
                for i in 0..k {
                    trial[i] = q[i] + lambda * step[i];
                }
                self.residual(pose, trial, r_trial)?;
                if sq(r_trial) <= (1.0 - 1e-4 * lambda) * base || lambda < 1e-3 {
                    break;
                }
                lambda *= 0.5;
            }
            q.copy_from_slice(trial);
            r.copy_from_slice(r_trial);
        }
        let now = norm(r);
        if now <= tol && self.stands(pose, q)? {
            return Ok(Ok(MAX_ITERATIONS));
        }
        if now < least {
            least = now;
            best.copy_from_slice(q);
        }
        Ok(Err(least))
    }

    /// The residual a solve converges to: 1e-9 of the rover's weight.
    fn tolerance(&self) -> f64 {
        1e-9 * (self.model.total_mass() * self.model.gravity).max(1e-12)
    }

    /// The forward-difference Jacobian of the residual at `q` (whose
    /// residual is `r`) into `jac`, row-major; `trial` and `r_trial` are
    /// scratch.
    fn difference_jacobian(
        &mut self,
        pose: [f64; 3],
        q: &[f64],
        r: &[f64],
        trial: &mut [f64],
        r_trial: &mut [f64],
        jac: &mut [f64],
    ) -> Result<(), QuasiStaticError> {
        let k = q.len();
        for c in 0..k {
            let h = 1e-7 * (1.0 + q[c].abs());
            trial.copy_from_slice(q);
            trial[c] += h;
            self.residual(pose, trial, r_trial)?;
            for row in 0..k {
                jac[row * k + c] = (r_trial[row] - r[row]) / h;
            }
        }
        Ok(())
    }

    /// Whether the rover stands at the equilibrium `q`: at least three
    /// wheels on the ground, not in a line, with the centre of mass's
    /// projection inside their support polygon. An equilibrium on two
    /// wheels (a diagonal) or on one is a balance that the slightest
    /// disturbance tips, not a rest: Newton–Raphson finds such balances,
    /// and the rover does not stay in them.
    fn stands(&mut self, pose: [f64; 3], q: &[f64]) -> Result<bool, QuasiStaticError> {
        if self.accept_balance {
            return Ok(true);
        }
        let mut r = core::mem::take(&mut self.r_check);
        let out = self.residual(pose, q, &mut r);
        self.r_check = r;
        out?;
        let centre = self.centre_of_mass(pose, q);
        let points: Vec<(usize, [f64; 2])> = (0..self.model.wheels.len())
            .filter(|&k| self.loads[k].force[2] > 0.0)
            .map(|k| (k, [self.points[k][0], self.points[k][1]]))
            .collect();
        Ok(convex_hull(&points).len() >= 3 && outside_support(&points, centre).is_none())
    }

    /// The horizontal projection of the centre of mass at pose and `q`.
    fn centre_of_mass(&self, pose: [f64; 3], q: &[f64]) -> [f64; 2] {
        let model = self.model;
        let rot = Attitude::new(q[1], q[2], pose[2]).rotation();
        let mut centre = [pose[0] * model.body.mass, pose[1] * model.body.mass];
        for b in &model.bodies {
            let u = b.position.value(&q[3..]);
            for (i, c) in centre.iter_mut().enumerate() {
                *c += b.mass * (pose[i] + (0..3).map(|j| rot[i][j] * u[j]).sum::<f64>());
            }
        }
        centre.map(|c| c / model.total_mass())
    }

    /// Why no equilibrium was found at `pose`, judged at the iterate of
    /// least residual: the centre of mass outside the support polygon of
    /// the loaded wheels (the rover tips), no wheel on the ground, or
    /// neither (Newton–Raphson did not converge).
    fn diagnose(&mut self, pose: [f64; 3], iterations: usize, residual: f64) -> QuasiStaticError {
        let model = self.model;
        let q = self.scratch.best.clone();
        let mut r = vec![0.0; q.len()];
        if let Err(e) = self.residual(pose, &q, &mut r) {
            return e;
        }
        let touching: Vec<usize> = (0..model.wheels.len())
            .filter(|&k| self.loads[k].force[2] > 0.0)
            .collect();
        if touching.is_empty() {
            return QuasiStaticError::NoContact {
                x: pose[0],
                y: pose[1],
            };
        }
        let centre = self.centre_of_mass(pose, &q);
        let points: Vec<(usize, [f64; 2])> = touching
            .iter()
            .map(|&k| (k, [self.points[k][0], self.points[k][1]]))
            .collect();
        let on_stops: Vec<usize> = model
            .coordinates
            .iter()
            .zip(&q[3..])
            .enumerate()
            .filter(|(_, (c, v))| **v < c.min || **v > c.max)
            .map(|(i, _)| i)
            .collect();
        match outside_support(&points, centre) {
            Some((edge, outside)) => QuasiStaticError::Tips(Box::new(Tipping {
                x: pose[0],
                y: pose[1],
                edge,
                outside,
                touching,
                on_stops,
            })),
            None => QuasiStaticError::NoConvergence {
                x: pose[0],
                y: pose[1],
                iterations,
                residual,
            },
        }
    }
}

/// Where `centre` lies outside the convex hull of `points` (wheel, X, Y):
/// the wheels of the hull's edge (or the corner, or the lone point) it lies
/// beyond and its distance from it \[m\]; `None` inside (within 1e-9 m).
/// Two or more points in a line make a segment, whose distance is the one
/// reported.
fn outside_support(points: &[(usize, [f64; 2])], centre: [f64; 2]) -> Option<(Vec<usize>, f64)> {
    let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    // Distance from the centre to segment ab, with the nearer end when the
    // foot falls outside it.
    let to_segment = |a: [f64; 2], b: [f64; 2]| {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            ((centre[0] - a[0]) * dx + (centre[1] - a[1]) * dy) / len2
        } else {
            0.0
        };
        let t = t.clamp(0.0, 1.0);
        (dist(centre, [a[0] + t * dx, a[1] + t * dy]), t)
    };
    let hull = convex_hull(points);
    let near = |i: usize, j: usize| {
        let (a, b) = (hull[i], hull[j]);
        let (d, t) = to_segment(a.1, b.1);
        let wheels = if t <= 0.0 {
            vec![a.0]
        } else if t >= 1.0 {
            vec![b.0]
        } else {
            let mut w = vec![a.0, b.0];
            w.sort_unstable();
            w
        };
        (wheels, d)
    };
    match hull.len() {
        0 => None,
        1 => Some((vec![hull[0].0], dist(centre, hull[0].1))),
        2 => Some(near(0, 1)),
        n => {
            // Counter-clockwise: the centre is outside an edge it lies to
            // the right of; the nearest such edge is the one it tips over.
            let mut found: Option<(Vec<usize>, f64)> = None;
            for i in 0..n {
                let (a, b) = (hull[i].1, hull[(i + 1) % n].1);
                let cross = (b[0] - a[0]) * (centre[1] - a[1]) - (b[1] - a[1]) * (centre[0] - a[0]);
                if cross < -1e-9 * dist(a, b) {
                    let (w, d) = near(i, (i + 1) % n);
                    if found.as_ref().is_none_or(|f| d < f.1) {
                        found = Some((w, d));
                    }
                }
            }
            found
        }
    }
}

/// The convex hull of points (wheel, X, Y), counter-clockwise (Andrew's
/// monotone chain); collinear points give the segment's two ends.
fn convex_hull(points: &[(usize, [f64; 2])]) -> Vec<(usize, [f64; 2])> {
    let mut p = points.to_vec();
    p.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]).then(a.1[1].total_cmp(&b.1[1])));
    if p.len() < 3 {
        return p;
    }
    let turn = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<(usize, [f64; 2])> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        for &pt in p.iter() {
            while hull.len() >= start + 2
                && turn(hull[hull.len() - 2].1, hull[hull.len() - 1].1, pt.1) <= 0.0
            {
                hull.pop();
            }
            hull.push(pt);
        }
        hull.pop();
        if pass == 0 {
            p.reverse();
        }
    }
    hull
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
    solver.accept_balance = true;
    solver.solve([0.0; 3])?;
    let mut loads = vec![0.0; model.wheels.len()];
    solver.normal_forces([0.0; 3], &mut loads)?;
    Ok(FlatGround {
        coordinates: solver.q[3..].to_vec(),
        loads,
        pose: solver.coordinates([0.0; 3], &solver.q),
    })
}
