//! Generalized forces in pseudo-coordinates (MODEL.md §5, paper eq. 20–23).
//!
//! A force with body components f applied at a point moving with `T_P·w`
//! contributes `T_Pᵀ·f`; a moment μ on a member turning with `U·w`
//! contributes `Uᵀ·μ`.

use crate::attitude::Attitude;
use crate::linalg::{V3, add, cross, dot, mul_t, scale};
use crate::model::{Coordinate, Model, MotorMount, Spring};
use crate::scalar::Scalar;
use crate::workspace::Workspace;

/// Loads on one wheel, inertial components (see [`crate::plant::WheelLoad`]).
#[derive(Clone, Copy, Debug)]
pub struct Load<S> {
    /// Resultant contact force at G_j \[N\].
    pub force: V3<S>,
    /// Moment about G_j on the carrying member, axle component removed [N·m].
    pub moment: V3<S>,
    /// Motor reaction on its stator [N·m].
    pub stator_torque: V3<S>,
}

/// Add `T_jᵀ·f` (force f, body components, applied at G_j) to `q`.
pub fn add_point_force<S: Scalar>(ws: &Workspace<S>, j: usize, f: V3<S>, q: &mut [S]) {
    let m = ws.m;
    let uf = cross(ws.u[j], f);
    for k in 0..3 {
        q[k] += f[k];
        q[3 + k] += uf[k];
    }
    for i in 0..m {
        q[6 + i] += dot(ws.s[j * m + i], f);
    }
}

/// Add the generalized force of a force f (body components) applied at a
/// point P of the member carrying body j, P = G_j + `offset` (body
/// components): the force at G_j plus the moment `offset × f` on the member.
pub fn add_member_point_force<S: Scalar>(
    ws: &Workspace<S>,
    j: usize,
    offset: V3<S>,
    f: V3<S>,
    q: &mut [S],
) {
    add_point_force(ws, j, f, q);
    add_member_moment(ws, j, cross(offset, f), q);
}

/// Add `U_jᵀ·μ` (moment μ, body components, on the member carrying body j) to `q`.
pub fn add_member_moment<S: Scalar>(ws: &Workspace<S>, j: usize, mu: V3<S>, q: &mut [S]) {
    let m = ws.m;
    for k in 0..3 {
        q[3 + k] += mu[k];
    }
    for i in 0..m {
        q[6 + i] += dot(ws.a[j * m + i], mu);
    }
}

/// Gravity (the paper's −f3, eq. 20): the body's weight at G, each carried
/// body's weight at G_j, `−g·(m_B·[Rᵀe_Z; 0; 0] + Σ_j m_j·T_jᵀ·Rᵀe_Z)`.
pub fn add_gravity<S: Scalar>(model: &Model, ws: &Workspace<S>, att: &Attitude<S>, q: &mut [S]) {
    let up = att.up_in_body();
    let g = S::cst(model.gravity);
    let wb = scale(-(g * S::cst(model.body.mass)), up);
    for k in 0..3 {
        q[k] += wb[k];
    }
    for (j, body) in model.bodies.iter().enumerate() {
        if body.mass != 0.0 {
            add_point_force(ws, j, scale(-(g * S::cst(body.mass)), up), q);
        }
    }
}

/// Width over which bump-stop damping ramps in [rad or m]: damping starting
/// at full strength the instant the stop is touched would make the force
/// jump; 1e-4 is far below any travel and keeps the law continuous.
pub const STOP_DAMPING_RAMP: f64 = 1e-4;

/// Generalized force along one suspension coordinate (MODEL.md §3–§4):
/// spring, damper and bump stops.
/// ```text
/// Q = f_s(y − y0) − c·ẏ + Q_stop,   f_s = −k·(y − y0) or the tabulated law
/// Q_stop = min(0, −k_s·p⁺ − c_s·r⁺·ẏ) + max(0, k_s·p⁻ − c_s·r⁻·ẏ)
/// p⁺ = max(y − y_max, 0), p⁻ = max(y_min − y, 0), r = min(p/ε, 1)
/// ```
/// The stop never pulls (the min/max clamp) and its damping ramps in over ε.
pub fn coordinate_force<S: Scalar>(coord: &Coordinate, neutral: S, y: S, yd: S) -> S {
    let d = y - neutral;
    let spring = match &coord.spring {
        Spring::None => S::zero(),
        Spring::Linear { stiffness } => -(S::cst(*stiffness) * d),
        Spring::Table { deflection, force } => table_force(deflection, force, d),
    };
    let zero = S::zero();
    let one = S::one();
    let ks = S::cst(coord.stop_stiffness);
    let cs = S::cst(coord.stop_damping);
    let eps = S::cst(1.0 / STOP_DAMPING_RAMP);
    let over = (y - S::cst(coord.max)).max(zero);
    let under = (S::cst(coord.min) - y).max(zero);
    let stop_hi = (-(ks * over) - cs * (over * eps).min(one) * yd).min(zero);
    let stop_lo = (ks * under - cs * (under * eps).min(one) * yd).max(zero);
    spring - S::cst(coord.damping) * yd + stop_hi + stop_lo
}

/// Piecewise-linear spring law as a sum of hinges (branch-free, so it traces):
/// `f(d) = f_0 + s_0·(d − d_0) + Σ_k (s_k − s_{k−1})·max(d − d_k, 0)`,
/// extended with the end slopes beyond the table.
fn table_force<S: Scalar>(defl: &[f64], force: &[f64], d: S) -> S {
    let n = defl.len().min(force.len());
    if n < 2 {
        return S::cst(force.first().copied().unwrap_or(0.0));
    }
    let slope = |k: usize| (force[k + 1] - force[k]) / (defl[k + 1] - defl[k]);
    let mut f = S::cst(force[0]) + S::cst(slope(0)) * (d - S::cst(defl[0]));
    for k in 1..n - 1 {
        let ds = slope(k) - slope(k - 1);
        f += S::cst(ds) * (d - S::cst(defl[k])).max(S::zero());
    }
    f
}

/// Suspension forces on rows 6.. of `q` for coordinates y, rates ẏ and spring
/// neutrals `neutral`.
pub fn add_suspension<S: Scalar>(model: &Model, neutral: &[S], y: &[S], yd: &[S], q: &mut [S]) {
    for (i, c) in model.coordinates.iter().enumerate() {
        q[6 + i] += coordinate_force(c, neutral[i], y[i], yd[i]);
    }
}

/// Wheel loads (the paper's f4, MODEL.md §7): F at G_j through `T_jᵀ`, the
/// contact moment on the carrier through `U_jᵀ`, the motor reaction on the
/// carrier (hub motor) or on the body (body motor).
pub fn add_wheel_loads<S: Scalar>(
    model: &Model,
    ws: &Workspace<S>,
    att: &Attitude<S>,
    loads: &[Load<S>],
    q: &mut [S],
) {
    let r = att.rotation();
    // Motor reactions on the body, summed in inertial components and
    // rotated once.
    let mut on_body: Option<V3<S>> = None;
    for (wheel, load) in model.wheels.iter().zip(loads) {
        let j = wheel.body;
        add_point_force(ws, j, mul_t(&r, load.force), q);
        match wheel.motor {
            // Both act on the carrier: one rotation, one mapping.
            MotorMount::Hub => {
                let mu = add(load.moment, load.stator_torque);
                add_member_moment(ws, j, mul_t(&r, mu), q);
            }
            MotorMount::Body => {
                add_member_moment(ws, j, mul_t(&r, load.moment), q);
                on_body = Some(match on_body {
                    Some(sum) => add(sum, load.stator_torque),
                    None => load.stator_torque,
                });
            }
        }
    }
    if let Some(tau) = on_body {
        let tau = mul_t(&r, tau);
        for k in 0..3 {
            q[3 + k] += tau[k];
        }
    }
}
