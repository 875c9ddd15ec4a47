//! The mass matrix and its derivatives (MODEL.md §4, paper eq. 11–19, 26).
//!
//! ```text
//! M = blockdiag(m_B·I₃, J_B, 0) + Σ_j ( m_j·T_jᵀ·T_j + U_jᵀ·J_j·U_j )
//! T_j = [I₃, ũ_jᵀ, S_j]        U_j = [0, I₃, A_j]   (A_j columns a_ij)
//! ```
//! M depends only on y. Rows and columns follow w = [v, Ω, ẏ].

use crate::linalg::{V3, cross, mul};
use crate::model::Model;
use crate::scalar::Scalar;
use crate::workspace::Workspace;

/// Row k of T_j as a function of the column: T_j[k][col].
#[inline]
fn t_entry<S: Scalar>(ws: &Workspace<S>, j: usize, k: usize, col: usize) -> S {
    let u = ws.u[j];
    match col {
        0..=2 => {
            if k == col {
                S::one()
            } else {
                S::zero()
            }
        }
        // ũᵀ = −ũ; ũ·e_c = u × e_c
        3..=5 => {
            let mut e = [S::zero(); 3];
            e[col - 3] = S::one();
            -cross(u, e)[k]
        }
        _ => ws.s[j * ws.m + col - 6][k],
    }
}

/// U_j[k][col] (member angular velocity map, eq. 16).
#[inline]
fn u_entry<S: Scalar>(ws: &Workspace<S>, j: usize, k: usize, col: usize) -> S {
    match col {
        0..=2 => S::zero(),
        3..=5 => {
            if k == col - 3 {
                S::one()
            } else {
                S::zero()
            }
        }
        _ => ws.a[j * ws.m + col - 6][k],
    }
}

/// Assemble M(y) into `ws.mass` (row-major). `body_kinematics` must have run.
pub fn mass_matrix<S: Scalar>(model: &Model, ws: &mut Workspace<S>) {
    let n = ws.dof;
    let mut mass = core::mem::take(&mut ws.mass);
    for v in mass.iter_mut() {
        *v = S::zero();
    }
    for k in 0..3 {
        mass[k * n + k] += S::cst(model.body.mass);
        for l in 0..3 {
            mass[(3 + k) * n + 3 + l] += S::cst(model.body.inertia[k][l]);
        }
    }
    let mut t = [[S::zero(); MAX_DOF]; 3];
    for (j, body) in model.bodies.iter().enumerate() {
        let mj = S::cst(body.mass);
        if body.mass != 0.0 {
            fill_rows(ws, j, n, &mut t, t_entry);
            for a in 0..n {
                for b in a..n {
                    let v = mj * (t[0][a] * t[0][b] + t[1][a] * t[1][b] + t[2][a] * t[2][b]);
                    mass[a * n + b] += v;
                }
            }
        }
        if body.inertia.is_some() {
            fill_rows(ws, j, n, &mut t, u_entry);
            let jj = ws.inertia[j];
            for a in 3..n {
                let ja: V3<S> = [
                    jj[0][0] * t[0][a] + jj[0][1] * t[1][a] + jj[0][2] * t[2][a],
                    jj[1][0] * t[0][a] + jj[1][1] * t[1][a] + jj[1][2] * t[2][a],
                    jj[2][0] * t[0][a] + jj[2][1] * t[1][a] + jj[2][2] * t[2][a],
                ];
                for b in a..n {
                    mass[a * n + b] += t[0][b] * ja[0] + t[1][b] * ja[1] + t[2][b] * ja[2];
                }
            }
        }
    }
    for a in 0..n {
        for b in 0..a {
            mass[a * n + b] = mass[b * n + a];
        }
    }
    ws.mass = mass;
}

/// Largest supported N = 6 + m for the dense row buffers.
pub const MAX_DOF: usize = 32;

fn fill_rows<S: Scalar>(
    ws: &Workspace<S>,
    j: usize,
    n: usize,
    t: &mut [[S; MAX_DOF]; 3],
    entry: fn(&Workspace<S>, usize, usize, usize) -> S,
) {
    for (k, row) in t.iter_mut().enumerate() {
        for (col, v) in row.iter_mut().enumerate().take(n) {
            *v = entry(ws, j, k, col);
        }
    }
}

/// `p = M·w` into `ws.p`. `mass_matrix` must have run.
pub fn momentum<S: Scalar>(ws: &mut Workspace<S>, w: &[S]) {
    let n = ws.dof;
    for a in 0..n {
        let mut acc = S::zero();
        for b in 0..n {
            acc += ws.mass[a * n + b] * w[b];
        }
        ws.p[a] = acc;
    }
}

/// ∂M/∂y_i (row-major N×N into `out`), for tests and linearization; the
/// right-hand side never forms it (see [`crate::bias`]).
///
/// ```text
/// ∂T_j/∂y_i = [0, −skew(S_j[:, i]), ∂S_j/∂y_i]     (∂S_j/∂y_i has only column i: ∂²u_j/∂y_i²)
/// ∂(m·TᵀT)/∂y_i = m·(∂Tᵀ·T + Tᵀ·∂T)
/// ∂(UᵀJU)/∂y_i = ∂Uᵀ·J·U + Uᵀ·∂J·U + Uᵀ·J·∂U,  ∂J = α'·(ã·J − J·ã)
/// ```
pub fn mass_matrix_derivative<S: Scalar>(
    model: &Model,
    ws: &Workspace<S>,
    i: usize,
    out: &mut [S],
) {
    let n = ws.dof;
    let m = ws.m;
    for v in out.iter_mut() {
        *v = S::zero();
    }
    let mut t = [[S::zero(); MAX_DOF]; 3];
    let mut dt = [[S::zero(); MAX_DOF]; 3];
    for (j, body) in model.bodies.iter().enumerate() {
        if body.mass != 0.0 {
            fill_rows(ws, j, n, &mut t, t_entry);
            let si = ws.s[j * m + i];
            for k in 0..3 {
                for col in 0..n {
                    dt[k][col] = S::zero();
                }
            }
            // ∂(−ũ)/∂y_i · e_c = −(S_i × e_c)
            for c in 0..3 {
                let mut e = [S::zero(); 3];
                e[c] = S::one();
                let d = cross(si, e);
                for k in 0..3 {
                    dt[k][3 + c] = -d[k];
                }
            }
            for k in 0..3 {
                dt[k][6 + i] = ws.h[j * m + i][k];
            }
            let mj = S::cst(body.mass);
            for a in 0..n {
                for b in 0..n {
                    let mut v = S::zero();
                    for k in 0..3 {
                        v += dt[k][a] * t[k][b] + t[k][a] * dt[k][b];
                    }
                    out[a * n + b] += mj * v;
                }
            }
        }
        if body.inertia.is_some() {
            fill_rows(ws, j, n, &mut t, u_entry);
            for k in 0..3 {
                for col in 0..n {
                    dt[k][col] = S::zero();
                }
                dt[k][6 + i] = ws.da[j * m + i][k];
            }
            let jj = ws.inertia[j];
            // ∂J/∂y_i
            let mut djj = [[S::zero(); 3]; 3];
            if let Some((coord, axis, rate)) = ws.inertia_rate[j]
                && coord == i
            {
                let e: V3<S> = crate::linalg::v3(axis);
                for c in 0..3 {
                    let mut ec = [S::zero(); 3];
                    ec[c] = S::one();
                    // column c of ã·J and of J·ã
                    let left = cross(e, [jj[0][c], jj[1][c], jj[2][c]]);
                    let right = mul(&jj, cross(e, ec));
                    for r in 0..3 {
                        djj[r][c] = rate * (left[r] - right[r]);
                    }
                }
            }
            for a in 0..n {
                for b in 0..n {
                    let mut v = S::zero();
                    for k in 0..3 {
                        for l in 0..3 {
                            v += dt[k][a] * jj[k][l] * t[l][b]
                                + t[k][a] * djj[k][l] * t[l][b]
                                + t[k][a] * jj[k][l] * dt[l][b];
                        }
                    }
                    out[a * n + b] += v;
                }
            }
        }
    }
}
