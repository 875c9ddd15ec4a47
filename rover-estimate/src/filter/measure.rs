//! What each sensor should read at the estimate, and its gradient: the
//! measurement functions `h(y)` and their rows `H = ∂h/∂δ` in error
//! coordinates (the attitude's columns against δθ).

use rover_dynamics::linalg::{M3, cross, dot, mul, mul_t};

use super::noise::ImuNoise;
use super::{ATTITUDE, Layout};
use crate::rotation::{cross3, rotation, skew};

/// `row ← row·S⁻¹`: a gradient against the model's `y` (Euler angles)
/// made a gradient against the error state (δθ), `δe = T⁻¹·δθ`.
pub(crate) fn to_error_coordinates(row: &mut [f64], t_inv: &M3<f64>) {
    let e = [row[3], row[4], row[5]];
    for j in 0..3 {
        row[3 + j] = e[0] * t_inv[0][j] + e[1] * t_inv[1][j] + e[2] * t_inv[2][j];
    }
}

/// The gyros' readings and rows: `h = C·Ω + b_g` (IMU axes), `C` the
/// body-to-IMU rotation; each of the 3 rows of `rows` is `len` long.
pub(crate) fn gyro(
    layout: &Layout,
    y: &[f64],
    bias: &[f64; 6],
    imu: &ImuNoise,
    rows: &mut [f64],
) -> [f64; 3] {
    let (n, len) = (layout.n, layout.len);
    let omega = [y[n + 3], y[n + 4], y[n + 5]];
    let body = mul(&imu.to_imu, omega);
    rows[..3 * len].iter_mut().for_each(|v| *v = 0.0);
    for axis in 0..3 {
        let row = &mut rows[axis * len..(axis + 1) * len];
        row[n + 3..n + 6].copy_from_slice(&imu.to_imu[axis]);
        row[layout.gyro_bias() + axis] = 1.0;
    }
    [0, 1, 2].map(|a| body[a] + bias[a])
}

/// The accelerometers' readings and rows: the specific force at the
/// IMU's point P, `r` from G in body axes,
/// ```text
/// a_P = v̇ + Ω×v + Ω̇×r + Ω×(Ω×r)         (body components)
/// h   = C·(a_P − Rᵀ·g) + b_a,   g = (0, 0, −g)
/// ```
/// with `v̇`, `Ω̇` the model's right-hand side `f` and their gradient its
/// Jacobian's `ẇ` rows, exact; the kinematic terms differentiated by
/// hand (`∂(Ω×(Ω×r))/∂Ω = (Ω·r)·I + Ω·rᵀ − 2·r·Ωᵀ`), the gravity's turn
/// with the attitude in error coordinates (`∂(Rᵀe_Z)/∂δθ = Rᵀ·ẽ_Z`).
pub(crate) fn accelerometer(
    layout: &Layout,
    (y, f, jac): (&[f64], &[f64], &[f64]),
    bias: &[f64; 6],
    imu: &ImuNoise,
    gravity: f64,
    t_inv: &M3<f64>,
    rows: &mut [f64],
) -> [f64; 3] {
    let (n, dim, len) = (layout.n, layout.dim, layout.len);
    let v = [y[n], y[n + 1], y[n + 2]];
    let omega = [y[n + 3], y[n + 4], y[n + 5]];
    let v_dot = [f[n], f[n + 1], f[n + 2]];
    let omega_dot = [f[n + 3], f[n + 4], f[n + 5]];
    let r = imu.position;
    let c = &imu.to_imu;
    let rot = rotation(&y[ATTITUDE]);
    let up = mul_t(&rot, [0.0, 0.0, 1.0]);
    let mut a = [0.0; 3];
    let centripetal = cross(omega, cross(omega, r));
    let transport = cross(omega, v);
    let euler = cross(omega_dot, r);
    for i in 0..3 {
        a[i] = v_dot[i] + transport[i] + euler[i] + centripetal[i] + gravity * up[i];
    }
    let reading = mul(c, a);
    // ∂(Ω×(Ω×r))/∂Ω, column k.
    let omega_r = dot(omega, r);
    let centripetal_gradient = |k: usize| -> [f64; 3] {
        [0, 1, 2].map(|i| {
            f64::from(u8::from(i == k)) * omega_r + omega[i] * r[k] - 2.0 * r[i] * omega[k]
        })
    };
    rows[..3 * len].iter_mut().for_each(|v| *v = 0.0);
    for j in 0..dim {
        let jv = [
            jac[n * dim + j],
            jac[(n + 1) * dim + j],
            jac[(n + 2) * dim + j],
        ];
        let jw = [
            jac[(n + 3) * dim + j],
            jac[(n + 4) * dim + j],
            jac[(n + 5) * dim + j],
        ];
        let turn = cross3(jw, r);
        let mut d = [jv[0] + turn[0], jv[1] + turn[1], jv[2] + turn[2]];
        if (n..n + 3).contains(&j) {
            let mut e = [0.0; 3];
            e[j - n] = 1.0;
            let t = cross(omega, e);
            (0..3).for_each(|i| d[i] += t[i]);
        } else if (n + 3..n + 6).contains(&j) {
            let k = j - n - 3;
            let mut e = [0.0; 3];
            e[k] = 1.0;
            let t = cross(e, v);
            let cg = centripetal_gradient(k);
            (0..3).for_each(|i| d[i] += t[i] + cg[i]);
        }
        let d = mul(c, d);
        for axis in 0..3 {
            rows[axis * len + j] = d[axis];
        }
    }
    // ∂(g·Rᵀe_Z)/∂δθ = g·Rᵀ·ẽ_Z, in IMU axes.
    let ez = skew([0.0, 0.0, 1.0]);
    for axis in 0..3 {
        let row = &mut rows[axis * len..(axis + 1) * len];
        to_error_coordinates(row, t_inv);
        for k in 0..3 {
            // (C·Rᵀ·ẽ_Z)[axis][k]
            let column = [ez[0][k], ez[1][k], ez[2][k]];
            let body = mul_t(&rot, column);
            row[3 + k] += gravity * dot(c[axis], body);
        }
        row[layout.accel_bias() + axis] = 1.0;
    }
    [0, 1, 2].map(|i| reading[i] + bias[3 + i])
}
