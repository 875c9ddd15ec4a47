//! Velocity-dependent terms of the equations of motion (MODEL.md §5, paper
//! eq. 25–28): `b = −Ṁ·w − f1 + f2`.
//!
//! The paper writes b through the momentum `p = M·w` (f1, eq. 27), the
//! rate of M and ∂M/∂y_i (f2). Summed, these are the Newton–Euler
//! (Kane) form: each body's acceleration at ẇ = 0, pulled back by its
//! partial velocities — the same vector, with no `M·w`, no Ṁ and fewer
//! operations (swing4's generated right-hand side: 787 → 699 multiplications).
//!
//! ```text
//! V_j = T_j·w = v + Ω×u_j + u̇_j,   u̇_j = S_j·ẏ
//! a_j = Ω×u̇_j + Σ_i ∂²u_j/∂y_i²·ẏ_i² + Ω×V_j         (acceleration at ẇ = 0)
//! −b  = [m_B·Ω×v; Ω×J_B·Ω; 0] + Σ_j m_j·T_jᵀ·a_j + Σ_j U_jᵀ·τ_j
//! τ_j = J_j·Σ_i ∂a_ij/∂y_i·ẏ_i² + J̇_j·Ω_j + Ω×L_j,  Ω_j = Ω + Σ_i a_ij·ẏ_i,  L_j = J_j·Ω_j
//! J̇_j·Ω_j = α'·ẏ_c·(e×L_j − J_j·(e×Ω_j))              (member turning about e)
//! ```
//! T_jᵀ·f = [f; u_j×f; S_j[:, i]·f], U_jᵀ·τ = [0; τ; a_ij·τ]. The two forms
//! agree identically (e.g. the rotation rows: `Σ m_j(u̇_j×V_j + u_j×A_j) +
//! v×p_v + Ω×p_Ω − Σ m_j u_j×(A_j + Ω×V_j) = Σ m_j (u̇_j + v + Ω×u_j)×V_j
//! = Σ m_j V_j×V_j = 0`); `tests/dynamics.rs` holds the result against
//! the paper's form built from [`crate::mass::mass_matrix_derivative`]
//! (itself checked against finite differences of M) and against Lagrange's
//! equations in ordinary coordinates. [`sub_f1`] (the paper's f1 alone) is kept for the simplified level,
//! which drops Ṁ and f2 but keeps f1.

use crate::kinematics::body_velocity;
use crate::linalg::{V3, add, cross, dot, mul, scale, sub, v3};
use crate::mass::momentum;
use crate::model::Model;
use crate::scalar::Scalar;
use crate::workspace::Workspace;

/// Subtract the gyroscopic and transport terms (eq. 27) from `out`:
/// `f1 = [Ω̃·p_v; ṽ·p_v + Ω̃·p_Ω; 0]`, `p = M·w` (M in `ws.mass`).
pub fn sub_f1<S: Scalar>(ws: &mut Workspace<S>, w: &[S], out: &mut [S]) {
    let omega: V3<S> = [w[3], w[4], w[5]];
    let vel: V3<S> = [w[0], w[1], w[2]];
    momentum(ws, w);
    let pv = [ws.p[0], ws.p[1], ws.p[2]];
    let pw = [ws.p[3], ws.p[4], ws.p[5]];
    let f1v = cross(omega, pv);
    let f1w = add(cross(vel, pv), cross(omega, pw));
    for k in 0..3 {
        out[k] -= f1v[k];
        out[3 + k] -= f1w[k];
    }
}

/// Add `−Ṁ·w − f1 + f2` to `out` (length N) in its Newton–Euler form
/// (see the module docs). `body_kinematics` must have run; M is not used.
pub fn add_bias<S: Scalar>(model: &Model, ws: &mut Workspace<S>, w: &[S], out: &mut [S]) {
    let m = ws.m;
    let vel: V3<S> = [w[0], w[1], w[2]];
    let omega: V3<S> = [w[3], w[4], w[5]];
    let yd = &w[6..];
    // The body: m_B·Ω×v on the translation rows, Ω×J_B·Ω on the rotation rows.
    let body = scale(S::cst(model.body.mass), cross(omega, vel));
    let gyro = cross(omega, mul(&crate::linalg::m3(&model.body.inertia), omega));
    for k in 0..3 {
        out[k] -= body[k];
        out[3 + k] -= gyro[k];
    }
    for (j, carried) in model.bodies.iter().enumerate() {
        if carried.mass != 0.0 {
            // a_j = Ω×u̇_j + Σ_i ∂²u_j/∂y_i²·ẏ_i² + Ω×V_j, pulled back by T_jᵀ.
            let vj = body_velocity(ws, j, w);
            let mut udot = [S::zero(); 3];
            let mut acc = [S::zero(); 3];
            for i in 0..m {
                udot = add(udot, scale(yd[i], ws.s[j * m + i]));
                acc = add(acc, scale(yd[i] * yd[i], ws.h[j * m + i]));
            }
            let a = add(acc, cross(omega, add(udot, vj)));
            let f = scale(S::cst(carried.mass), a);
            let uf = cross(ws.u[j], f);
            for k in 0..3 {
                out[k] -= f[k];
                out[3 + k] -= uf[k];
            }
            for i in 0..m {
                out[6 + i] -= dot(ws.s[j * m + i], f);
            }
        }
        if carried.inertia.is_some() {
            // τ_j = J_j·Σ_i ∂a_ij/∂y_i·ẏ_i² + J̇_j·Ω_j + Ω×L_j, pulled back by U_jᵀ.
            let jj = ws.inertia[j];
            let mut oj = omega;
            let mut b = [S::zero(); 3];
            for i in 0..m {
                oj = add(oj, scale(yd[i], ws.a[j * m + i]));
                b = add(b, scale(yd[i] * yd[i], ws.da[j * m + i]));
            }
            let l = mul(&jj, oj);
            let mut tau = add(mul(&jj, b), cross(omega, l));
            if let Some((c, axis, rate)) = ws.inertia_rate[j] {
                let e: V3<S> = v3(axis);
                let jdot = scale(rate * yd[c], sub(cross(e, l), mul(&jj, cross(e, oj))));
                tau = add(tau, jdot);
            }
            for k in 0..3 {
                out[3 + k] -= tau[k];
            }
            for i in 0..m {
                out[6 + i] -= dot(ws.a[j * m + i], tau);
            }
        }
    }
}
