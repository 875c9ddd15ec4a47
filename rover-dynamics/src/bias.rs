//! Velocity-dependent terms of the equations of motion (MODEL.md §5, paper
//! eq. 25–28): `b = −Ṁ·w − f1 + f2`.
//!
//! Ṁ·w and f2 are computed per body from the body's velocity and
//! acceleration terms instead of forming ∂M/∂y_i (O(n·m) instead of
//! O(m·N²)); [`crate::mass::mass_matrix_derivative`] is the explicit form the
//! tests hold this against.
//!
//! ```text
//! V_j = T_j·w,  u̇_j = S_j·ẏ,  A_j = Ṫ_j·w = −u̇_j×Ω + Σ_i ∂²u_j/∂y_i²·ẏ_i²
//! Ṁ·w  = Σ_j m_j·(Ṫ_jᵀ·V_j + T_jᵀ·A_j)
//!      = Σ_j m_j·[A_j;  u̇_j×V_j + u_j×A_j;  ẏ_i·∂²u_j/∂y_i²·V_j + S_j[:,i]·A_j]
//! f2_i = ½·wᵀ·∂M/∂y_i·w = Σ_j m_j·V_j·(−S_j[:,i]×Ω + ∂²u_j/∂y_i²·ẏ_i)
//! f1   = [Ω̃·p_v;  ṽ·p_v + Ω̃·p_Ω;  0],  p = M·w                        (eq. 27)
//! ```
//! For a body with inertia J_j(y) on a member with Ω_j = U_j·w, L_j = J_j·Ω_j:
//! ```text
//! Ṁ·w += [0;  K;  a_ij·K + ẏ_i·∂a_ij/∂y_i·L_j],  K = J̇_j·Ω_j + J_j·Σ_i ∂a_ij/∂y_i·ẏ_i²
//! J̇_j·Ω_j = α'·ẏ_c·(e×L_j − J_j·(e×Ω_j))
//! f2_i += ẏ_i·∂a_ij/∂y_i·L_j + [i = c]·α'·Ω_j·(e×L_j)
//! ```

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

/// Add `−Ṁ·w − f1 + f2` to `out` (length N). `mass_matrix` must have run.
pub fn add_bias<S: Scalar>(model: &Model, ws: &mut Workspace<S>, w: &[S], out: &mut [S]) {
    let m = ws.m;
    let omega: V3<S> = [w[3], w[4], w[5]];
    let yd = &w[6..];
    sub_f1(ws, w, out);
    for (j, body) in model.bodies.iter().enumerate() {
        if body.mass != 0.0 {
            let mj = S::cst(body.mass);
            let u = ws.u[j];
            let vj = body_velocity(ws, j, w);
            let mut udot = [S::zero(); 3];
            let mut acc = [S::zero(); 3];
            for i in 0..m {
                udot = add(udot, scale(yd[i], ws.s[j * m + i]));
                acc = add(acc, scale(yd[i] * yd[i], ws.h[j * m + i]));
            }
            acc = sub(acc, cross(udot, omega));
            // −Ṁ·w
            let top = acc;
            let mid = add(cross(udot, vj), cross(u, acc));
            for k in 0..3 {
                out[k] -= mj * top[k];
                out[3 + k] -= mj * mid[k];
            }
            for i in 0..m {
                let si = ws.s[j * m + i];
                let hi = ws.h[j * m + i];
                let mdot = yd[i] * dot(hi, vj) + dot(si, acc);
                // f2_i
                let f2 = dot(
                    vj,
                    add(scale(-S::one(), cross(si, omega)), scale(yd[i], hi)),
                );
                out[6 + i] += mj * (f2 - mdot);
            }
        }
        if body.inertia.is_some() {
            let jj = ws.inertia[j];
            let mut oj = omega;
            let mut b = [S::zero(); 3];
            for i in 0..m {
                oj = add(oj, scale(yd[i], ws.a[j * m + i]));
                b = add(b, scale(yd[i] * yd[i], ws.da[j * m + i]));
            }
            let l = mul(&jj, oj);
            let mut k_vec = mul(&jj, b);
            let mut spin = None;
            if let Some((c, axis, rate)) = ws.inertia_rate[j] {
                let e: V3<S> = v3(axis);
                let jdot = scale(rate * yd[c], sub(cross(e, l), mul(&jj, cross(e, oj))));
                k_vec = add(k_vec, jdot);
                spin = Some((c, rate * dot(oj, cross(e, l))));
            }
            for k in 0..3 {
                out[3 + k] -= k_vec[k];
            }
            for i in 0..m {
                let ai = ws.a[j * m + i];
                let dai = ws.da[j * m + i];
                let mdot = dot(ai, k_vec) + yd[i] * dot(dai, l);
                let mut f2 = yd[i] * dot(dai, l);
                if let Some((c, v)) = spin
                    && c == i
                {
                    f2 += v;
                }
                out[6 + i] += f2 - mdot;
            }
        }
    }
}
