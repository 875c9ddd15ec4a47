//! The reduced fidelity levels of MODEL.md §9 (paper §6) that keep an ODE:
//! level 2, simplified, and level 3, linearized. (Level 4, quasi-static, has
//! no dynamics and lives in the runtime.)
//!
//! Both freeze T_j — so ũ_j, S_j and the member rates — at the rest
//! configuration y_c in M, in the gravity term and in the mapping of the
//! wheel loads: M is constant (factored once), Ṁ = 0, f2 = 0.
//!
//! ```text
//! simplified:  M_c·ẇ = −f1 + Q(x, w; T_c),                      ẋ = B(x)·w
//! linearized:  M_c·ẇ = Q(x_lin, w; T_c),  R ≈ Rz(ψ)·(I + skew([φ, θ, 0])),
//!              ẋ = B_lin(x)·w,  wheel centres from u_c + S_c·(y − y_ref)
//! ```
//! The linearized level is the paper's: R (eq. 4), Aᵀ (eq. 10) and the
//! gravity matrix C (eq. 30) all to first order in roll and pitch. Its
//! variant [`Fidelity::LinearizedExactRotation`] keeps R exact and takes only
//! the gravity direction and the angle rates to first order.
//! Dropping f1 drops the centripetal term Ω × p, which the paper accepts
//! for slow rovers.

use crate::attitude::Attitude;
use crate::forces::{Load, add_gravity, add_suspension, add_wheel_loads};
use crate::kinematics::{WheelKinematics, body_kinematics, position_rates};
use crate::linalg::{V3, add, cross, mul, scale};
use crate::mass::mass_matrix;
use crate::model::Model;
use crate::scalar::Scalar;
use crate::solve::{ldlt_factor, ldlt_substitute};
use crate::workspace::Workspace;

/// How much of the model a run keeps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Fidelity {
    /// Level 1: everything (MODEL.md §2–§7).
    #[default]
    Full,
    /// Level 2: T_j frozen at rest; M constant, Ṁ = f2 = 0.
    Simplified,
    /// Level 3, the paper's: as level 2, plus u_j tangent at rest, R, E⁻¹
    /// and the gravity direction to first order in roll and pitch, f1 = 0.
    Linearized,
    /// Level 3 with R exact: only the gravity direction and E⁻¹ to first
    /// order (wheel positions and the load mapping keep the exact rotation).
    LinearizedExactRotation,
}

impl Fidelity {
    /// The level's name as a scenario's `fidelity` writes it.
    pub fn name(self) -> &'static str {
        match self {
            Fidelity::Full => "full",
            Fidelity::Simplified => "simplified",
            Fidelity::Linearized => "linearized",
            Fidelity::LinearizedExactRotation => "linearized_exact_rotation",
        }
    }

    /// Level 3, in either form: u_j tangent at the reference, f1 = 0.
    pub fn is_linearized(self) -> bool {
        matches!(
            self,
            Fidelity::Linearized | Fidelity::LinearizedExactRotation
        )
    }
}

/// The frozen kinematics and the factored constant mass matrix.
#[derive(Clone, Debug)]
pub struct Frozen<S> {
    /// u_j(y_c), S_j(y_c), member rates at rest; second derivatives zero.
    pub ws: Workspace<S>,
    /// LDLᵀ factors of M(y_c).
    pub factor: alloc::vec::Vec<S>,
    /// The configuration frozen at, y_ref.
    pub y_ref: alloc::vec::Vec<S>,
}

impl<S: Scalar> Frozen<S> {
    /// Freeze `model` at its rest configuration y_c.
    pub fn new(model: &Model) -> Self {
        let rest: alloc::vec::Vec<f64> = model.coordinates.iter().map(|c| c.rest).collect();
        Self::at(model, &rest)
    }

    /// Freeze `model` at the configuration `y_ref` — for a loaded rover,
    /// its static equilibrium, about which it actually moves.
    pub fn at(model: &Model, y_ref: &[f64]) -> Self {
        let mut ws = Workspace::new(model);
        let rest: alloc::vec::Vec<S> = y_ref.iter().map(|&v| S::cst(v)).collect();
        body_kinematics(model, &rest, &mut ws);
        for v in ws.h.iter_mut().chain(ws.da.iter_mut()) {
            *v = [S::zero(); 3];
        }
        for r in ws.inertia_rate.iter_mut() {
            *r = None;
        }
        mass_matrix(model, &mut ws);
        let mut factor = ws.mass.clone();
        ldlt_factor(&mut factor, ws.dof);
        Self {
            ws,
            factor,
            y_ref: rest,
        }
    }
}

/// The attitude of a level.
pub fn attitude<S: Scalar>(level: Fidelity, x: &[S]) -> Attitude<S> {
    match level {
        Fidelity::Linearized => Attitude::linear(x[3], x[4], x[5]),
        Fidelity::LinearizedExactRotation => Attitude::linear_exact_rotation(x[3], x[4], x[5]),
        _ => Attitude::new(x[3], x[4], x[5]),
    }
}

/// `ẋ` and `ẇ` for levels 2 and 3 (for level 1 use [`crate::eom::derivatives`]).
pub fn reduced_derivatives<S: Scalar>(
    model: &Model,
    level: Fidelity,
    frozen: &mut Frozen<S>,
    neutral: &[S],
    x: &[S],
    w: &[S],
    loads: &[Load<S>],
    xdot: &mut [S],
    wdot: &mut [S],
) {
    let n = frozen.ws.dof;
    let att = attitude(level, x);
    let ws = &mut frozen.ws;
    let mut rhs = core::mem::take(&mut ws.rhs);
    for v in rhs.iter_mut() {
        *v = S::zero();
    }
    if level == Fidelity::Simplified {
        // −f1 with p = M_c·w.
        crate::bias::sub_f1(ws, w, &mut rhs);
    }
    add_gravity(model, ws, &att, &mut rhs);
    add_suspension(model, neutral, &x[6..], &w[6..], &mut rhs);
    add_wheel_loads(model, ws, &att, loads, &mut rhs);
    ldlt_substitute(&frozen.factor, &mut rhs, n);
    wdot.copy_from_slice(&rhs);
    frozen.ws.rhs = rhs;
    match level {
        Fidelity::Linearized | Fidelity::LinearizedExactRotation => {
            let vel = mul(&att.rotation(), [w[0], w[1], w[2]]);
            let rates = att.rates([w[3], w[4], w[5]]);
            xdot[..3].copy_from_slice(&vel);
            xdot[3..6].copy_from_slice(&rates);
            xdot[6..].copy_from_slice(&w[6..]);
        }
        _ => position_rates(x, w, xdot),
    }
}

/// Wheel-centre kinematics of level 3: `u_j ≈ u_j(y_ref) + S_j(y_ref)·(y − y_ref)`,
/// tangent at the configuration frozen at (y_c for [`Frozen::new`]), with
/// the level's attitude (orientation polynomials kept exact). The spin axis
/// is a direction the contact search takes as a unit vector: with the
/// first-order R it is normalized (its length is 1 + O(φ²)).
pub fn linear_wheel_kinematics<S: Scalar>(
    model: &Model,
    level: Fidelity,
    frozen: &Frozen<S>,
    x: &[S],
    w: &[S],
    k: usize,
    steer: S,
) -> WheelKinematics<S> {
    let ws = &frozen.ws;
    let m = ws.m;
    let wheel = &model.wheels[k];
    let j = wheel.body;
    let y = &x[6..];
    let mut u: V3<S> = ws.u[j];
    let mut rel = [S::zero(); 3];
    for i in 0..m {
        u = add(u, scale(y[i] - frozen.y_ref[i], ws.s[j * m + i]));
        rel = add(rel, scale(w[6 + i], ws.s[j * m + i]));
    }
    let att = attitude(level, x);
    let r = att.rotation();
    let centre = add([x[0], x[1], x[2]], mul(&r, u));
    let body_vel = add(add([w[0], w[1], w[2]], cross([w[3], w[4], w[5]], u)), rel);
    let velocity = mul(&r, body_vel);
    let mut spin_axis = crate::kinematics::spin_axis(wheel, &r, y, steer);
    if att.linear_rotation {
        spin_axis = scale(S::one() / crate::linalg::norm(spin_axis), spin_axis);
    }

    WheelKinematics {
        centre,
        velocity,
        spin_axis,
    }
}
