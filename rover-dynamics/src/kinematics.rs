//! Suspension kinematics of the carried bodies and of the wheels (MODEL.md §3,
//! paper eq. 6–7, 12–16, 32–34).

use crate::attitude::Attitude;
use crate::linalg::{V3, add, axis_angle, cross, m3, mat_mul, mul, scale, transpose, v3};
use crate::model::Model;
use crate::scalar::Scalar;
use crate::workspace::Workspace;

/// Fill `ws.u`, `ws.s`, `ws.h`, `ws.a`, `ws.da` and the member inertias for
/// the suspension coordinates `y` (length m).
///
/// ```text
/// u_j = Σ_i Z_ij·[1, ξ_i, …]ᵀ            (eq. 32)
/// S_j[:, i] = ∂u_j/∂y_i                  (eq. 14, 34)
/// a_ij = axis·α'(y_i)                    (eq. 16: Ω_j = Ω + Σ_i a_ij·ẏ_i)
/// J_j(y) = R_m(y)·J_j·R_m(y)ᵀ            (R_m: rotation by α about axis)
/// ```
pub fn body_kinematics<S: Scalar>(model: &Model, y: &[S], ws: &mut Workspace<S>) {
    let m = ws.m;
    for v in
        ws.s.iter_mut()
            .chain(ws.h.iter_mut())
            .chain(ws.a.iter_mut())
            .chain(ws.da.iter_mut())
    {
        *v = [S::zero(); 3];
    }
    for (j, body) in model.bodies.iter().enumerate() {
        let (s, h) = (&mut ws.s[j * m..(j + 1) * m], &mut ws.h[j * m..(j + 1) * m]);
        ws.u[j] = body.position.eval(y, |i, d1, d2| {
            s[i] = add(s[i], d1);
            h[i] = add(h[i], d2);
        });
        ws.inertia_rate[j] = None;
        let mut rot = None;
        for r in &body.member {
            let mut rate = (S::zero(), S::zero());
            let angle = r
                .angle
                .eval(y, |_, d1, d2| rate = (rate.0 + d1, rate.1 + d2));
            let axis: V3<S> = v3(r.axis);
            ws.a[j * m + r.coord] = add(ws.a[j * m + r.coord], scale(rate.0, axis));
            ws.da[j * m + r.coord] = add(ws.da[j * m + r.coord], scale(rate.1, axis));
            rot = Some((r.coord, r.axis, angle, rate.0));
        }
        if let Some(j0) = &body.inertia {
            let j0 = m3::<S>(j0);
            ws.inertia[j] = match rot {
                Some((coord, axis, angle, rate)) => {
                    let rm = axis_angle(axis, angle);
                    ws.inertia_rate[j] = Some((coord, axis, rate));
                    mat_mul(&mat_mul(&rm, &j0), &transpose(&rm))
                }
                None => j0,
            };
        }
    }
}

/// Position rates `ẋ = B·w` (eq. 10, 24): `[R·v; E⁻¹·Ω; ẏ]`.
pub fn position_rates<S: Scalar>(x: &[S], w: &[S], xdot: &mut [S]) {
    let att = Attitude::new(x[3], x[4], x[5]);
    let r = att.rotation();
    let vel = mul(&r, [w[0], w[1], w[2]]);
    let rates = att.rates([w[3], w[4], w[5]]);
    xdot[..3].copy_from_slice(&vel);
    xdot[3..6].copy_from_slice(&rates);
    xdot[6..].copy_from_slice(&w[6..]);
}

/// Velocity of carried body j relative to G in body components,
/// `V_j = v + Ω×u_j + Σ_i S_j[:, i]·ẏ_i = T_j·w` (eq. 12–14).
pub fn body_velocity<S: Scalar>(ws: &Workspace<S>, j: usize, w: &[S]) -> V3<S> {
    let m = ws.m;
    let mut vj = add([w[0], w[1], w[2]], cross([w[3], w[4], w[5]], ws.u[j]));
    for i in 0..m {
        vj = add(vj, scale(w[6 + i], ws.s[j * m + i]));
    }
    vj
}

/// Kinematics of one wheel, generic over the scalar (see [`crate::plant::WheelState`]).
#[derive(Clone, Copy, Debug)]
pub struct WheelKinematics<S> {
    /// Wheel centre r_Gj, inertial \[m\].
    pub centre: V3<S>,
    /// Absolute velocity of the centre, inertial [m/s].
    pub velocity: V3<S>,
    /// Unit spin axis, inertial.
    pub spin_axis: V3<S>,
}

/// Wheel-centre kinematics of wheel k for steering angle `steer` (MODEL.md §3):
/// ```text
/// r_Gj = [X, Y, Z] + R·u_j        V_j = R·T_j·w
/// a_wj = R·R_wj·e_y,  R_wj = Rz(δ_j + ε_j(y))·Rx(γ_j(y))
/// ```
/// `body_kinematics` must have run for the same y.
pub fn wheel_kinematics<S: Scalar>(
    model: &Model,
    ws: &Workspace<S>,
    att: &Attitude<S>,
    x: &[S],
    w: &[S],
    k: usize,
    steer: S,
) -> WheelKinematics<S> {
    let wheel = &model.wheels[k];
    let j = wheel.body;
    let r = att.rotation();
    let centre = add([x[0], x[1], x[2]], mul(&r, ws.u[j]));
    let velocity = mul(&r, body_velocity(ws, j, w));
    let spin_axis = spin_axis(wheel, &r, &x[6..], steer);
    WheelKinematics {
        centre,
        velocity,
        spin_axis,
    }
}

/// Unit spin axis of a wheel, inertial: `a_w = R·Rz(δ + ε(y))·Rx(γ(y))·e_y`
/// (MODEL.md §3); δ is ignored for a wheel that is not steerable.
pub fn spin_axis<S: Scalar>(
    wheel: &crate::model::Wheel,
    r: &crate::linalg::M3<S>,
    y: &[S],
    steer: S,
) -> V3<S> {
    let steer = if wheel.steerable { steer } else { S::zero() };
    let camber = wheel.camber.value(y);
    let heading = steer + wheel.toe.value(y);
    let (sh, ch) = (heading.sin(), heading.cos());
    let (sg, cg) = (camber.sin(), camber.cos());
    mul(r, [-(sh * cg), ch * cg, sg])
}
