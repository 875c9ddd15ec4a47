//! The attitude's error coordinates: the model keeps Euler angles
//! `e = [φ, θ, ψ]` (MODEL.md §1–§2), the filter's error state a small
//! rotation δθ in inertial axes, `R_true = exp(δθ×)·R_est`. From
//! `Ṙ = R·Ω×` and `Ω = E·ė`, an increment of the angles turns the body by
//! ```text
//! R(e + δe) = R(e)·exp((E·δe)×) = exp((R·E·δe)×)·R(e)   (to first order)
//! δθ = T·δe,   T = R·E,   T⁻¹ = E⁻¹·Rᵀ
//! ```
//! T is singular only where E is (cos φ = 0); the covariance of δθ never
//! meets it.

use rover_dynamics::attitude::Attitude;
use rover_dynamics::linalg::{M3, cross, dot, mat_mul, transpose};

/// The attitude of `[φ, θ, ψ]`: the plant's own sines and cosines.
fn attitude(e: &[f64]) -> Attitude<f64> {
    Attitude::new(e[0], e[1], e[2])
}

/// `R = Rz(ψ)·Rx(φ)·Ry(θ)` of the angles `e = [φ, θ, ψ]`: body
/// components → inertial components.
pub(crate) fn rotation(e: &[f64]) -> M3<f64> {
    attitude(e).rotation()
}

/// `E` of `Ω = E·[φ̇, θ̇, ψ̇]` (MODEL.md §2, eq. 9).
fn euler_rate_matrix(e: &[f64]) -> M3<f64> {
    let a = attitude(e);
    [
        [a.cth, 0.0, -a.sth * a.cphi],
        [0.0, 1.0, a.sphi],
        [a.sth, 0.0, a.cth * a.cphi],
    ]
}

/// `E⁻¹`, column by column from the plant's own angle rates
/// (`Attitude::rates`, eq. 9).
fn euler_rate_matrix_inverse(e: &[f64]) -> M3<f64> {
    let a = attitude(e);
    let columns = [
        a.rates([1.0, 0.0, 0.0]),
        a.rates([0.0, 1.0, 0.0]),
        a.rates([0.0, 0.0, 1.0]),
    ];
    transpose(&columns)
}

/// The map between Euler increments and the small rotation at `e`:
/// `(T, T⁻¹)` with `δθ = T·δe`.
pub(crate) fn error_map(e: &[f64]) -> (M3<f64>, M3<f64>) {
    let r = rotation(e);
    let t = mat_mul(&r, &euler_rate_matrix(e));
    let t_inv = mat_mul(&euler_rate_matrix_inverse(e), &transpose(&r));
    (t, t_inv)
}

/// `ã`, the skew matrix of `a` (`ã·b = a × b`).
pub(crate) fn skew(a: [f64; 3]) -> M3<f64> {
    [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]]
}

/// `exp(δθ×)` (Rodrigues), exact for any angle.
pub(crate) fn exp(v: [f64; 3]) -> M3<f64> {
    let angle2 = dot(v, v);
    let angle = libm::sqrt(angle2);
    // sin α/α and (1 − cos α)/α², by their series below 1e-4 rad.
    let (a, b) = if angle < 1e-4 {
        (1.0 - angle2 / 6.0, 0.5 - angle2 / 24.0)
    } else {
        (libm::sin(angle) / angle, (1.0 - libm::cos(angle)) / angle2)
    };
    let k = skew(v);
    let k2 = mat_mul(&k, &k);
    let mut r = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = f64::from(u8::from(i == j)) + a * k[i][j] + b * k2[i][j];
        }
    }
    r
}

/// The rotation vector of `r` (the inverse of [`exp`]), for angles below
/// π.
pub(crate) fn log(r: &M3<f64>) -> [f64; 3] {
    let axis2 = [r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]];
    let sin2 = libm::sqrt(dot(axis2, axis2)); // 2·sin α
    let cos2 = r[0][0] + r[1][1] + r[2][2] - 1.0; // 2·cos α
    let angle = libm::atan2(sin2, cos2);
    // α / (2 sin α), by its series near 0.
    let scale = if sin2 < 1e-8 {
        0.5 + angle * angle / 12.0
    } else {
        angle / sin2
    };
    axis2.map(|v| scale * v)
}

/// The angles `[φ, θ, ψ]` of `r = Rz(ψ)·Rx(φ)·Ry(θ)`, ψ taken within π
/// of `psi_near` (a turning rover's yaw runs past ±π).
pub(crate) fn euler(r: &M3<f64>, psi_near: f64) -> [f64; 3] {
    // Third row [−cφ·sθ, sφ, cφ·cθ]; second column's [−sψ·cφ, cψ·cφ].
    let phi = libm::asin(r[2][1].clamp(-1.0, 1.0));
    let theta = libm::atan2(-r[2][0], r[2][2]);
    let psi = libm::atan2(-r[0][1], r[1][1]);
    [phi, theta, psi_near + wrap(psi - psi_near)]
}

/// `a` wrapped into (−π, π].
pub(crate) fn wrap(a: f64) -> f64 {
    let two_pi = 2.0 * core::f64::consts::PI;
    let w = a - two_pi * libm::floor((a + core::f64::consts::PI) / two_pi);
    // floor puts −π at −π: move it to π.
    if w <= -core::f64::consts::PI {
        w + two_pi
    } else {
        w
    }
}

/// The rotation nearest `r`, orthonormal to rounding: one Newton–Schulz
/// step `R·(3I − RᵀR)/2`, enough for the drift of a product of exact
/// rotations (dead reckoning's attitude, turned every sample).
pub(crate) fn orthonormalize(r: &M3<f64>) -> M3<f64> {
    let rtr = mat_mul(&transpose(r), r);
    let mut m = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = 0.5 * (3.0 * f64::from(u8::from(i == j)) - rtr[i][j]);
        }
    }
    mat_mul(r, &m)
}

/// `a × b`.
pub(crate) fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    cross(a, b)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn is_identity(p: &M3<f64>) -> bool {
        (0..3).all(|i| (0..3).all(|j| (p[i][j] - f64::from(u8::from(i == j))).abs() < 1e-14))
    }

    #[test]
    fn euler_rate_matrix_and_its_inverse_are_inverse() {
        let e = [0.3, -0.7, 2.9];
        let p = mat_mul(&euler_rate_matrix(&e), &euler_rate_matrix_inverse(&e));
        assert!(is_identity(&p));
    }

    #[test]
    fn exp_and_log_are_inverse_and_euler_recovers_the_angles() {
        for v in [
            [0.0, 0.0, 0.0],
            [1e-9, -2e-9, 3e-9],
            [0.3, -0.2, 1.1],
            [-2.0, 1.0, 0.5],
        ] {
            let back = log(&exp(v));
            assert!(
                (0..3).all(|i| (back[i] - v[i]).abs() < 1e-12),
                "{v:?} {back:?}"
            );
        }
        let e = [0.2, -0.4, 3.0];
        let back = euler(&rotation(&e), 3.0);
        assert!((0..3).all(|i| (back[i] - e[i]).abs() < 1e-12));
        // A yaw past π stays on the side of the previous one.
        let back = euler(&rotation(&[0.0, 0.0, 3.3]), 3.2);
        assert!((back[2] - 3.3).abs() < 1e-12);
    }

    #[test]
    fn orthonormalize_removes_drift() {
        let mut r = rotation(&[0.3, -0.2, 1.0]);
        r[0][0] *= 1.0 + 1e-6;
        let o = orthonormalize(&r);
        let oto = mat_mul(&transpose(&o), &o);
        let worst = (0..9).fold(0.0f64, |w, k| {
            let (i, j) = (k / 3, k % 3);
            w.max((oto[i][j] - f64::from(u8::from(i == j))).abs())
        });
        assert!(worst < 1e-11, "{worst}");
    }

    /// `R(e + δe) ≈ exp((T·δe)×)·R(e)`, to second order in δe.
    #[test]
    fn error_map_turns_euler_increments_into_small_rotations() {
        let e = [0.3, -0.5, 1.2];
        let (t, t_inv) = error_map(&e);
        let d = [1e-6, -2e-6, 1.5e-6];
        let moved = rotation(&[e[0] + d[0], e[1] + d[1], e[2] + d[2]]);
        let turn = log(&mat_mul(&moved, &transpose(&rotation(&e))));
        let mapped = [0, 1, 2].map(|i| dot(t[i], d));
        assert!((0..3).all(|i| (turn[i] - mapped[i]).abs() < 1e-11));
        assert!(is_identity(&mat_mul(&t, &t_inv)));
    }

    #[test]
    fn wrap_keeps_angles_within_pi() {
        assert!((wrap(3.5) - (3.5 - 2.0 * core::f64::consts::PI)).abs() < 1e-15);
        assert_eq!(wrap(-core::f64::consts::PI), core::f64::consts::PI);
        assert_eq!(wrap(0.25), 0.25);
    }
}
