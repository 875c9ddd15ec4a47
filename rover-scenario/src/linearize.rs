//! Small motions of a rover about a steady state on flat ground — parked,
//! driving straight or turning steadily — : the state matrix of the whole
//! right-hand side, its input matrix and its modes.
//!
//! Parked, the rover stands on flat ground with no command (motors off, no
//! steering, passive suspension) at its quasi-static equilibrium
//! ([`flat_ground_pose`]) refined on the dynamics, `w = 0`; at speed, or
//! turning under a constant command, every rate but those of X, Y and ψ
//! vanishes at the steady state (found by Newton on the right-hand side,
//! [`linearize_at`]). For small `z = y − y_e`, `ż ≈ A·z` with
//! `A = ∂(ẋ, ẇ)/∂(x, w)` taken by central differences of the
//! very [`RoverSystem::rhs`] a run integrates: plant, contact search and
//! wheel law together. A generated plant's exact Jacobian is at fixed wheel
//! loads, but what makes a rover stand on its wheels is how the loads change
//! with the state, and the contact search has no closed-form derivative, so
//! the whole right-hand side is differenced. Tests hold the differences to
//! the exact Jacobian in free flight and the linear response to a nonlinear
//! run started a little off the equilibrium.
//!
//! The eigenvalues of `A` are the rover's modes: oscillatory pairs (bounce,
//! pitch, roll, suspension) with their natural frequency and damping ratio,
//! real ones (the wheels' lateral creep, overdamped suspensions; a positive
//! one means the rover falls over), and neutral ones, motions with no
//! restoring force (X, Y and heading on flat ground; rolling too, unless
//! the scenario's contact has a rolling resistance).

use nalgebra::{Complex, DMatrix, DVector};
use rover_dynamics::plant::Plant;
use rover_dynamics::{HeightField, Model};

use crate::scenario::ContactConfig;
use rover_integrate::OdeSystem;
use rover_runtime::control::{ControlError, Controller, ControllerConfig};
use rover_runtime::quasi_static::{QuasiStaticError, flat_ground_pose};
use rover_runtime::sim::{RoverSystem, SimError};
use rover_terrain::Terrain;

/// Largest forward speed linearized about \[m/s\] (in either direction):
/// far beyond any planetary rover.
pub const MAX_SPEED: f64 = 100.0;

/// The equilibrium's error, with advice that applies to linearizing: modes
/// exist only about a rover that stands on its wheels.
fn equilibrium_message(e: &QuasiStaticError) -> String {
    match e {
        QuasiStaticError::NoConvergence {
            x,
            y,
            iterations,
            residual,
        } => format!(
            "Newton–Raphson did not converge at X = {x:.3} m, Y = {y:.3} m after {iterations} iterations (residual {residual:.3e} N): the rover does not stand on its wheels on flat ground; check with `rover check` that its wheels are below the body and its springs carry its weight, or simulate it to see where it goes"
        ),
        other => other.to_string(),
    }
}

/// Why a rover could not be linearized.
#[derive(Debug, thiserror::Error)]
pub enum LinearizeError {
    /// No static equilibrium on flat ground.
    #[error("no static equilibrium on flat ground: {}", equilibrium_message(.0))]
    Equilibrium(#[from] QuasiStaticError),
    /// The right-hand side failed at or near the equilibrium.
    #[error("the right-hand side failed near the equilibrium: {0}")]
    Rhs(#[from] SimError),
    /// The (empty) controller of a parked rover does not fit the model.
    #[error("{0}")]
    Control(#[from] ControlError),
    /// The operating point asked for is not a steady state.
    #[error("{0}")]
    NotSteady(String),
    /// A difference quotient came out NaN or infinite.
    #[error(
        "∂f/∂{state} is not finite: the right-hand side is not differentiable there \
         (a wheel on the edge of contact?)"
    )]
    NotFinite {
        /// The state whose column failed.
        state: String,
    },
}

/// Below this |λ| \[1/s\] a mode counts as neutral: a motion with no
/// restoring force (a time constant or period above 100 s means nothing for
/// a rover's dynamics, and the difference quotients of the exactly neutral
/// directions come out below 1e-5 for the built-in rovers).
pub const NEUTRAL_RATE: f64 = 1e-2;

/// A pseudo-velocity is listed among a mode's dominant ones when it carries
/// at least this share of the mode's kinetic energy.
pub const DOMINANT_SHARE: f64 = 0.1;

/// How a mode moves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ModeKind {
    /// A decaying (or growing) oscillation: a complex pair, listed once.
    Oscillatory,
    /// A real eigenvalue: creep, overdamped return, or a fall if positive.
    Real,
    /// |λ| < [`NEUTRAL_RATE`]: no restoring force.
    Neutral,
}

/// One mode of the linearized rover.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Mode {
    /// Oscillatory, real or neutral.
    pub kind: ModeKind,
    /// The eigenvalue λ \[1/s\] (Im λ > 0 for an oscillatory pair).
    pub eigenvalue: [f64; 2],
    /// Undamped natural frequency |λ|/2π \[Hz\].
    pub natural_hz: f64,
    /// Damped frequency Im λ/2π \[Hz\] (0 for real modes).
    pub damped_hz: f64,
    /// Damping ratio −Re λ/|λ| (1 for a decaying real mode, < 0 unstable).
    pub damping_ratio: f64,
    /// Time constant −1/Re λ \[s\] (negative: the mode grows).
    pub time_constant: f64,
    /// The position part of the eigenvector, `[re, im]` per coordinate
    /// (m or rad), scaled so that its largest entry is 1 (phase 0); empty
    /// for neutral modes.
    pub shape: Vec<[f64; 2]>,
    /// Each pseudo-velocity's share of the mode's kinetic energy,
    /// `M_ii·|w_i|² / Σ_j M_jj·|w_j|²` (units agree, unlike the shape's m
    /// and rad); empty for neutral modes.
    pub energy: Vec<f64>,
    /// The pseudo-velocities with an energy share ≥ [`DOMINANT_SHARE`],
    /// largest first, with their shares.
    pub dominant: Vec<(String, f64)>,
}

/// The linearized rover.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Linearization {
    /// Names of the states, as the run CSV's columns (`X` … `ym`, `vx` …
    /// `dym`), then the controller's integrals that act: `zeta`, the speed
    /// loop's, when it has a gain, and a heading hold's `zeta_heading` and
    /// `zeta_line`.
    pub states: Vec<String>,
    /// The steady state's coordinates x_e (its velocities are in
    /// [`state`](Linearization::state)).
    pub equilibrium: Vec<f64>,
    /// Its forward speed V \[m/s\].
    pub speed: f64,
    /// The whole state there, `[x_e; w_e; ζ]` (the right-hand side's `y`).
    pub state: Vec<f64>,
    /// max |f_i| at the steady state over the rates that must vanish (all
    /// but those of X, Y, ψ) [m/s, rad/s, m/s² or rad/s²]: how steady it is.
    pub residual: f64,
    /// How far the quasi-static solution was from this equilibrium, the
    /// largest change of a coordinate when refined on the right-hand side
    /// (m or rad).
    pub refinement: f64,
    /// The state matrix A, row-major (`a[i][j] = ∂f_i/∂z_j`).
    pub a: Vec<Vec<f64>>,
    /// Names of the inputs of [`b`](Linearization::b): the spring neutrals
    /// `y0_1` … `y0_m` (what an active suspension moves, MODEL.md §8), the
    /// motor torques `tau_1` … `tau_k` and the steering angles `delta_j` of
    /// the steerable wheels (the open-loop commands of
    /// [`RoverSystem::set_torques`] and [`RoverSystem::set_steering`],
    /// on top of the loops in the linearization).
    pub inputs: Vec<String>,
    /// The input matrix B = ∂f/∂u over those inputs, row-major (a row per
    /// state of [`a`](Linearization::a); the columns of coordinates without
    /// a spring are zero).
    pub b: Vec<Vec<f64>>,
    /// Every mode: oscillatory by frequency, then real by |λ|, then neutral.
    pub modes: Vec<Mode>,
}

/// Where a rover is linearized: steady driving on flat ground (parked at
/// speed 0), straight or in a steady turn, with the scenario's contact and
/// controllers.
#[derive(Clone, Debug, Default)]
pub struct OperatingPoint {
    /// Forward speed V \[m/s\]; 0 parks the rover.
    pub speed: f64,
    /// Contact search, wheel law and rolling resistance.
    pub contact: ContactConfig,
    /// The controllers in the loop; none: motors off. A speed loop's
    /// set-point becomes `speed`; the steering is none or a heading hold
    /// (straight: its set-point at t = 0 and line give the heading and the
    /// position), or a constant slip or Ackermann command (a steady turn).
    /// The active suspension is sampled, not part of the right-hand side, so
    /// it is not in the linearization.
    pub control: ControllerConfig,
}

/// Linearize `model`, with `plant` as its plant, about its equilibrium
/// parked on flat ground (default contact search and wheel law, motors off).
pub fn linearize<P: Plant>(model: &Model, plant: P) -> Result<Linearization, LinearizeError> {
    linearize_at(model, plant, &OperatingPoint::default())
}

/// [`linearize`] about an [`OperatingPoint`]: at speed, with a scenario's
/// contact table and controllers (then the modes are the closed loop's).
pub fn linearize_at<P: Plant>(
    model: &Model,
    plant: P,
    point: &OperatingPoint,
) -> Result<Linearization, LinearizeError> {
    let n = model.dof();
    let (mut sys, mut y) = operating_system(model, plant, point)?;
    // The controller's integrals are states of the loop when they act (the
    // speed loop's only with a gain).
    let mut names: Vec<String> =
        rover_runtime::row::Columns::new(model.m(), 0).names()[1..=2 * n].to_vec();
    let mut states: Vec<usize> = (0..2 * n).collect();
    for (k, (name, acts)) in sys.control.state_names().into_iter().enumerate() {
        if acts {
            states.push(2 * n + k);
            names.push(name.into());
        }
    }
    let quasi_static = y[..n].to_vec();
    let parked = point.speed == 0.0 && !turns(&point.control.steering);
    let held_speed = point.control.speed.is_none();
    let residual = steady(&mut sys, &mut y, &names, &states, parked, held_speed)?;
    let a = state_matrix(&mut sys, &y, &names, &states)?;
    let mut mass = vec![0.0; n * n];
    sys.plant.mass_matrix(&y[..n], &mut mass);
    let inertia: Vec<f64> = (0..n).map(|i| mass[i * n + i]).collect();
    let modes = modes(&a, &inertia, &names[n..2 * n]);
    let (inputs, b) = input_matrix(&mut sys, &y, model, &states)?;
    Ok(Linearization {
        states: names,
        equilibrium: y[..n].to_vec(),
        speed: point.speed,
        state: y.clone(),
        residual,
        refinement: y[..n]
            .iter()
            .zip(&quasi_static)
            .fold(0.0, |m: f64, (p, q)| m.max((p - q).abs())),
        a: rows(&a),
        inputs,
        b: rows(&b),
        modes,
    })
}

/// A matrix as its rows, for the JSON.
fn rows(m: &DMatrix<f64>) -> Vec<Vec<f64>> {
    m.row_iter().map(|r| r.iter().copied().collect()).collect()
}

/// Newton steps on the steady state at most, after the quasi-static solve.
const MAX_SETTLE: usize = 12;

/// max |f| over the steady rows at which the steady state counts as found
/// [m/s², rad/s², m/s, rad/s].
const SETTLED: f64 = 1e-10;

/// max |f| over the steady rows below which a Newton solve that stops
/// short of [`SETTLED`] (a level whose rows cannot all vanish to rounding)
/// still counts as steady.
const STEADY_ENOUGH: f64 = 1e-6;

/// Refine `y` to a steady state of `sys`: every rate of `states` vanishes
/// but those of X, Y and ψ, which a rover driving on flat ground changes
/// steadily (straight: X, Y; turning: all three) and on which nothing
/// depends but a heading hold's line, held where the rover started. The
/// unknowns are the same states (the pose Z, φ, θ, y, the body and
/// suspension velocities, the integrals that act), or, `parked`, all but
/// the velocities, which stay exactly 0; with `held_speed` (no speed loop
/// to set it) v_x stays what it is, so that a rover whose motion decays
/// (coasting against rolling resistance) has no steady state instead of a
/// parked one. Newton steps with the
/// central-difference Jacobian of those rows, least-squares and
/// minimum-norm (by SVD: a motion with no restoring force, free rolling,
/// has no row to fix it, so it stays where it started), halved while they
/// do not lower max |f|. Returns max |f| over those rows.
fn steady<P: Plant, H: HeightField>(
    sys: &mut RoverSystem<P, H>,
    y: &mut [f64],
    names: &[String],
    states: &[usize],
    parked: bool,
    held_speed: bool,
) -> Result<f64, LinearizeError> {
    let n = sys.dof();
    let fixed: Vec<usize> = (0..states.len())
        .filter(|&c| !matches!(states[c], 0 | 1 | 5))
        .collect();
    let rows: Vec<usize> = fixed.iter().map(|&c| states[c]).collect();
    let moving: Vec<usize> = fixed
        .iter()
        .copied()
        .filter(|&c| !(parked && (n..2 * n).contains(&states[c])))
        .filter(|&c| !(held_speed && states[c] == n))
        .collect();
    // f: the rates at the accepted y; trial: at a step being tried.
    let (mut f, mut trial) = (vec![0.0; y.len()], vec![0.0; y.len()]);
    let residual = |sys: &mut RoverSystem<P, H>, y: &[f64], f: &mut [f64]| {
        sys.rhs(0.0, y, f)?;
        Ok::<f64, LinearizeError>(rows.iter().fold(0.0, |m: f64, &i| m.max(f[i].abs())))
    };
    let mut r = residual(sys, y, &mut f)?;
    for _ in 0..MAX_SETTLE {
        if r <= SETTLED {
            break;
        }
        let a = state_matrix(sys, y, names, states)?;
        let j = DMatrix::from_fn(rows.len(), moving.len(), |p, q| a[(fixed[p], moving[q])]);
        let rhs = DVector::from_fn(rows.len(), |p, _| -f[rows[p]]);
        let svd = j.svd(true, true);
        let cut = 1e-9 * svd.singular_values.max();
        let Ok(step) = svd.solve(&rhs, cut) else {
            break;
        };
        if !step.iter().all(|v| v.is_finite()) {
            break;
        }
        let start = y.to_vec();
        let mut scale = 1.0;
        let mut improved = false;
        for _ in 0..12 {
            for (q, &c) in moving.iter().enumerate() {
                let i = states[c];
                y[i] = start[i] + scale * step[q];
            }
            match residual(sys, y, &mut trial) {
                Ok(next) if next < r => {
                    r = next;
                    std::mem::swap(&mut f, &mut trial);
                    improved = true;
                    break;
                }
                _ => scale *= 0.5,
            }
        }
        if !improved {
            y.copy_from_slice(&start);
            break;
        }
    }
    if r > STEADY_ENOUGH {
        let worst = rows
            .iter()
            .map(|&i| (i, f[i].abs()))
            .max_by(|p, q| p.1.total_cmp(&q.1))
            .map_or(String::new(), |(i, v)| {
                let name = states
                    .iter()
                    .position(|&s| s == i)
                    .and_then(|c| names.get(c));
                format!(" (d{}/dt = {v:.2e})", name.map_or("?", |s| s.as_str()))
            });
        return Err(LinearizeError::NotSteady(format!(
            "no steady state found near the start: the rates stay at {r:.2e}{worst} after {MAX_SETTLE} Newton steps"
        )));
    }
    Ok(r)
}

/// B = ∂f/∂u at `y` over the states `states`, by central differences of
/// each input about the operating point, restored after: the spring
/// neutrals (step 1e-7 rad or m; they enter through the spring law only, so
/// linearly for linear springs), the motor torques (1e-6 N·m: the drawbar
/// pull τ/|G_jH| is linear below its friction limit) and the steerable
/// wheels' angles (1e-7 rad). Returns the inputs' names with B.
fn input_matrix<P: Plant, H: HeightField>(
    sys: &mut RoverSystem<P, H>,
    y: &[f64],
    model: &Model,
    states: &[usize],
) -> Result<(Vec<String>, DMatrix<f64>), LinearizeError> {
    let (m, k) = (model.m(), model.wheels.len());
    let steerable: Vec<usize> = (0..k).filter(|&j| model.wheels[j].steerable).collect();
    let mut names: Vec<String> = (1..=m).map(|i| format!("y0_{i}")).collect();
    names.extend((1..=k).map(|j| format!("tau_{j}")));
    names.extend(steerable.iter().map(|j| format!("delta_{}", j + 1)));
    let mut b = DMatrix::zeros(states.len(), names.len());
    let (mut plus, mut minus) = (vec![0.0; y.len()], vec![0.0; y.len()]);
    let mut column = |sys: &mut RoverSystem<P, H>,
                      col: usize,
                      h: f64,
                      set: &mut dyn FnMut(&mut RoverSystem<P, H>, f64)|
     -> Result<(), LinearizeError> {
        set(sys, h);
        let up = sys.rhs(0.0, y, &mut plus);
        set(sys, -h);
        let down = sys.rhs(0.0, y, &mut minus);
        set(sys, 0.0);
        up?;
        down?;
        for (r, &i) in states.iter().enumerate() {
            b[(r, col)] = (plus[i] - minus[i]) / (2.0 * h);
        }
        Ok(())
    };
    for (j, c) in model.coordinates.iter().enumerate() {
        let h = 1e-7 * c.neutral.abs().max(1.0);
        column(sys, j, h, &mut |sys, d| {
            sys.plant.set_spring_neutral(j, c.neutral + d)
        })?;
    }
    // The commands of the operating point are zero: each column moves one.
    let mut command = vec![0.0; k];
    for j in 0..k {
        column(sys, m + j, 1e-6, &mut |sys, d| {
            command[j] = d;
            // One finite value per wheel: cannot fail.
            let _ = sys.set_torques(&command);
        })?;
    }
    for (c, &j) in steerable.iter().enumerate() {
        column(sys, m + k + c, 1e-7, &mut |sys, d| {
            command[j] = d;
            let _ = sys.set_steering(&command);
        })?;
    }
    Ok((names, b))
}

/// Whether the steering turns the rover (slip or Ackermann commands).
fn turns(steering: &rover_runtime::control::Steering) -> bool {
    use rover_runtime::control::Steering;
    matches!(steering, Steering::Slip { .. } | Steering::Ackermann(_))
}

/// The parked rover as a system (flat ground, default contact search and
/// wheel law, no command) and its equilibrium state `y_e = [x_e; 0; 0]`
/// (the controller's integrals last): what [`linearize`] differentiates.
pub fn parked<P: Plant>(
    model: &Model,
    plant: P,
) -> Result<(RoverSystem<P, Terrain>, Vec<f64>), LinearizeError> {
    operating_system(model, plant, &OperatingPoint::default())
}

/// The system of an [`OperatingPoint`] and its state before the steady
/// state is solved for: the parked pose, turned to the heading hold's
/// set-point and moved onto its line, driving horizontally at V, and for
/// Ackermann steering turning kinematically about its centre.
pub fn operating_system<P: Plant>(
    model: &Model,
    plant: P,
    point: &OperatingPoint,
) -> Result<(RoverSystem<P, Terrain>, Vec<f64>), LinearizeError> {
    use rover_runtime::control::{Profile, Steering};
    let n = model.dof();
    let not_steady = |why: &str| Err(LinearizeError::NotSteady(why.to_string()));
    if point.speed.is_nan() || point.speed.abs() > MAX_SPEED {
        return not_steady(&format!(
            "the speed {} m/s is not a finite number within ±{MAX_SPEED} m/s: give the forward speed in m/s (e.g. --speed 0.1)",
            point.speed
        ));
    }
    if point.control.commands.is_some() {
        return not_steady(
            "open-loop commands from a file change with time: linearize without `[control.commands]` (the input matrix B has the torque and steering columns)",
        );
    }
    let mut control = point.control.clone();
    if let Some(s) = &mut control.speed {
        s.speed = Profile::Constant(point.speed);
    }
    let mut x_e = flat_ground_pose(model)?;
    match &control.steering {
        Steering::None => {}
        Steering::Heading(h) => {
            // On the first line (the first leg of waypoints), along it.
            let (heading, origin) = h.line(0.0, 0);
            x_e[0] = origin[0];
            x_e[1] = origin[1];
            x_e[5] = heading;
        }
        Steering::Slip { delta_tau } => {
            if !matches!(delta_tau, Profile::Constant(_)) {
                return not_steady("a steady turn needs a constant `delta_tau`, not a time table");
            }
        }
        Steering::Ackermann(a) => {
            let constant = |p: &Option<Profile>| matches!(p, None | Some(Profile::Constant(_)));
            if !(constant(&a.radius) && constant(&a.front_left_deg)) {
                return not_steady(
                    "a steady turn needs a constant `radius` or `front_left_deg`, not a time table",
                );
            }
        }
    }
    let ground = point.contact.ground(Terrain::default(), model);
    let controller = Controller::new(control, model, 0.0)?;
    let sys = RoverSystem::new(plant, Some(ground), controller);
    let mut y = vec![0.0; sys.dim()];
    y[..n].copy_from_slice(&x_e);
    drive(&mut y, n, point.speed);
    // A kinematic turn about the Ackermann centre (x_c, 1/κ) as the start:
    // Ω_z = κ·V, and G slips sideways at −Ω_z·x_c so that x_c does not.
    let (kappa, centre_x) = sys.control.curvature(0.0);
    y[n + 5] = kappa * point.speed;
    y[n + 1] -= y[n + 5] * centre_x;
    Ok((sys, y))
}

/// Set the body velocity of `y` to a horizontal one along the heading ψ
/// whose forward body component is `speed` (what a speed loop holds): with
/// the body pitched, `[V, 0, 0]` in body axes would climb or sink.
fn drive(y: &mut [f64], n: usize, speed: f64) {
    let att = rover_dynamics::attitude::Attitude::new(y[3], y[4], y[5]);
    let r = att.rotation();
    let (s, c) = y[5].sin_cos();
    // Rᵀ·(cos ψ, sin ψ, 0): the heading in body axes.
    let along: [f64; 3] = [0, 1, 2].map(|k| r[0][k] * c + r[1][k] * s);
    let scale = if speed == 0.0 { 0.0 } else { speed / along[0] };
    for k in 0..3 {
        y[n + k] = scale * along[k];
    }
}

/// `∂f/∂y` of `sys` at `y` over the states `states` (indices into y, rows
/// and columns in that order; `0..2N` for x and w with the integrals
/// held), by central differences; `names` label the columns in errors.
///
/// Steps: 1e-7 for coordinates (m, rad: a ten-thousandth of a typical
/// tyre deflection, well inside the smooth part of the contact) and 1e-8
/// for rates, each scaled by max(1, |y_j|). The rates' step is small
/// because the cornering force at standstill, `−μF_n·sgn α·(1 − e^{−C|α|/μF_n})`
/// with `α ≈ V_c/v_ε`, has an `α·|α|` term that central differences do not
/// cancel: their error grows in proportion to the step (5e-4 of the lateral
/// damping at 1e-6 m/s, 5e-6 at 1e-8; roundoff stays below 1e-7).
pub fn state_matrix<P: Plant, H: HeightField>(
    sys: &mut RoverSystem<P, H>,
    y: &[f64],
    names: &[String],
    states: &[usize],
) -> Result<DMatrix<f64>, LinearizeError> {
    let n = sys.dof();
    let dim = states.len();
    let mut a = DMatrix::zeros(dim, dim);
    let mut probe = y.to_vec();
    let (mut plus, mut minus) = (vec![0.0; y.len()], vec![0.0; y.len()]);
    for (c, &j) in states.iter().enumerate() {
        let h = if j < n { 1e-7 } else { 1e-8 } * y[j].abs().max(1.0);
        probe[j] = y[j] + h;
        sys.rhs(0.0, &probe, &mut plus)?;
        probe[j] = y[j] - h;
        sys.rhs(0.0, &probe, &mut minus)?;
        probe[j] = y[j];
        for (r, &i) in states.iter().enumerate() {
            let d = (plus[i] - minus[i]) / (2.0 * h);
            if !d.is_finite() {
                return Err(LinearizeError::NotFinite {
                    state: names.get(c).cloned().unwrap_or_else(|| j.to_string()),
                });
            }
            a[(r, c)] = d;
        }
    }
    Ok(a)
}

/// The modes of `a` (states x, then w, then possibly the controller's
/// integrals); `inertia` is the diagonal of the mass matrix M (the kinetic
/// energy's weights of w) and `velocities` names the N states of w.
pub fn modes(a: &DMatrix<f64>, inertia: &[f64], velocities: &[String]) -> Vec<Mode> {
    let n = velocities.len();
    let mut out: Vec<Mode> = Vec::new();
    for lambda in a.complex_eigenvalues().iter().copied() {
        let magnitude = abs(lambda);
        let kind = if magnitude < NEUTRAL_RATE {
            ModeKind::Neutral
        } else if lambda.im.abs() > 1e-9 * magnitude {
            if lambda.im < 0.0 {
                continue; // the conjugate is listed
            }
            ModeKind::Oscillatory
        } else {
            ModeKind::Real
        };
        let vector = match kind {
            ModeKind::Neutral => None,
            _ => eigenvector(a, lambda),
        };
        let (shape, energy) = match &vector {
            Some(v) => (position_shape(v, n), energy_shares(v, inertia)),
            None => (Vec::new(), Vec::new()),
        };
        let dominant = dominant(&energy, velocities);
        let two_pi = 2.0 * std::f64::consts::PI;
        out.push(Mode {
            kind,
            eigenvalue: [
                lambda.re,
                if kind == ModeKind::Real {
                    0.0
                } else {
                    lambda.im
                },
            ],
            natural_hz: magnitude / two_pi,
            damped_hz: if kind == ModeKind::Oscillatory {
                lambda.im / two_pi
            } else {
                0.0
            },
            damping_ratio: if magnitude > 0.0 {
                -lambda.re / magnitude
            } else {
                0.0
            },
            time_constant: -1.0 / lambda.re,
            shape,
            energy,
            dominant,
        });
    }
    let rank = |m: &Mode| match m.kind {
        ModeKind::Oscillatory => 0,
        ModeKind::Real => 1,
        ModeKind::Neutral => 2,
    };
    out.sort_by(|p, q| {
        rank(p)
            .cmp(&rank(q))
            .then(p.natural_hz.total_cmp(&q.natural_hz))
    });
    out
}

/// The eigenvector of `a` for `lambda` by inverse iteration, shifted just
/// off λ so that the factorization exists; `None` if it fails.
fn eigenvector(a: &DMatrix<f64>, lambda: Complex<f64>) -> Option<DVector<Complex<f64>>> {
    let dim = a.nrows();
    let shift = lambda + Complex::new(1e-9 * abs(lambda).max(1.0), 0.0);
    let zero = Complex::new(0.0, 0.0);
    let m = DMatrix::from_fn(dim, dim, |i, j| {
        Complex::new(a[(i, j)], 0.0) - if i == j { shift } else { zero }
    });
    let lu = m.lu();
    // A fixed, generic start (not orthogonal to any structured eigenvector).
    let mut v = DVector::from_fn(dim, |i, _| Complex::new(1.0 + 0.1 * i as f64, 0.0));
    for _ in 0..3 {
        let next = lu.solve(&v)?;
        let norm = next.iter().map(|c| c.norm_sqr()).sum::<f64>().sqrt();
        if !(norm.is_finite() && norm > 0.0) {
            return None;
        }
        v = next / Complex::new(norm, 0.0);
    }
    Some(v)
}

/// The first `n` entries of `v`, scaled so that the largest is 1 with phase 0.
fn position_shape(v: &DVector<Complex<f64>>, n: usize) -> Vec<[f64; 2]> {
    let p = v.rows(0, n);
    let big = p
        .iter()
        .copied()
        .max_by(|x, y| abs(*x).total_cmp(&abs(*y)))
        .unwrap_or(Complex::new(0.0, 0.0));
    if abs(big) == 0.0 {
        return vec![[0.0, 0.0]; n];
    }
    p.iter()
        .map(|c| {
            let s = c / big;
            [s.re, s.im]
        })
        .collect()
}

/// Kinetic-energy shares of the velocity part of `v` (entries N … 2N − 1,
/// N = `inertia.len()`), weighted by the diagonal of M.
fn energy_shares(v: &DVector<Complex<f64>>, inertia: &[f64]) -> Vec<f64> {
    let n = inertia.len();
    let e: Vec<f64> = (0..n).map(|i| inertia[i] * v[n + i].norm_sqr()).collect();
    let total: f64 = e.iter().sum();
    if total > 0.0 {
        e.iter().map(|x| x / total).collect()
    } else {
        e
    }
}

/// |c| (num-complex's `norm` needs its std feature).
fn abs(c: Complex<f64>) -> f64 {
    c.re.hypot(c.im)
}

/// Names with an energy share ≥ [`DOMINANT_SHARE`], largest first.
fn dominant(energy: &[f64], names: &[String]) -> Vec<(String, f64)> {
    let mut idx: Vec<(usize, f64)> = energy
        .iter()
        .copied()
        .enumerate()
        .filter(|&(_, s)| s >= DOMINANT_SHARE)
        .collect();
    // Largest first; shares equal to 1e-6 (a symmetric rover's left and
    // right, equal up to rounding) in coordinate order, so that the order
    // does not depend on which back end rounded which way.
    let key = |s: f64| (s * 1e6).round();
    idx.sort_by(|p, q| key(q.1).total_cmp(&key(p.1)).then(p.0.cmp(&q.0)));
    idx.into_iter()
        .filter_map(|(i, s)| names.get(i).map(|name| (name.clone(), s)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_equilibrium_advises_what_applies_to_linearizing() {
        let e = LinearizeError::Equilibrium(QuasiStaticError::NoConvergence {
            x: 0.0,
            y: 0.0,
            iterations: 50,
            residual: 12.0,
        });
        let text = e.to_string();
        assert!(
            text.contains("does not stand on its wheels") && text.contains("rover check"),
            "{text}"
        );
        assert!(!text.contains("fidelity"), "{text}");
    }
}
