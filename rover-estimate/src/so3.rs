//! Rotations as 3×3 matrices, in the model's attitude convention
//! (docs/MODEL.md §1): `R = Rz(ψ)·Rx(φ)·Ry(θ)` takes body components to
//! inertial ones.

/// A 3×3 matrix, row-major.
pub type M3 = [[f64; 3]; 3];

/// The identity.
pub const IDENTITY: M3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// `R(φ, θ, ψ) = Rz(ψ)·Rx(φ)·Ry(θ)`.
pub fn from_euler(phi: f64, theta: f64, psi: f64) -> M3 {
    let (sf, cf) = libm::sincos(phi);
    let (st, ct) = libm::sincos(theta);
    let (sp, cp) = libm::sincos(psi);
    let a = [
        [ct, 0.0, st],
        [sf * st, cf, -sf * ct],
        [-cf * st, sf, cf * ct],
    ];
    [
        [
            cp * a[0][0] - sp * a[1][0],
            cp * a[0][1] - sp * a[1][1],
            cp * a[0][2] - sp * a[1][2],
        ],
        [
            sp * a[0][0] + cp * a[1][0],
            sp * a[0][1] + cp * a[1][1],
            sp * a[0][2] + cp * a[1][2],
        ],
        a[2],
    ]
}

/// The angles `[φ, θ, ψ]` of `R` (inverse of [`from_euler`] for |φ| < 90°):
/// the third row is `[−cφ·sθ, sφ, cφ·cθ]`, the second column's first two
/// entries `[−sψ·cφ, cψ·cφ]`.
pub fn to_euler(r: &M3) -> [f64; 3] {
    let phi = libm::asin(r[2][1].clamp(-1.0, 1.0));
    let theta = libm::atan2(-r[2][0], r[2][2]);
    let psi = libm::atan2(-r[0][1], r[1][1]);
    [phi, theta, psi]
}

/// `exp(v×)`, the rotation by the angle |v| about v (Rodrigues' formula).
pub fn exp(v: [f64; 3]) -> M3 {
    let angle2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    // sin(a)/a and (1 − cos a)/a², by their series near 0.
    let (a, b) = if angle2 < 1e-12 {
        (1.0 - angle2 / 6.0, 0.5 - angle2 / 24.0)
    } else {
        let angle = libm::sqrt(angle2);
        (libm::sin(angle) / angle, (1.0 - libm::cos(angle)) / angle2)
    };
    let k = skew(v);
    let k2 = mul(&k, &k);
    let mut r = IDENTITY;
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] += a * k[i][j] + b * k2[i][j];
        }
    }
    r
}

/// `v×`, the cross-product matrix.
pub fn skew(v: [f64; 3]) -> M3 {
    [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]]
}

/// `a·b`.
pub fn mul(a: &M3, b: &M3) -> M3 {
    let mut c = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    c
}

/// `a·v`.
pub fn apply(a: &M3, v: [f64; 3]) -> [f64; 3] {
    [
        a[0][0] * v[0] + a[0][1] * v[1] + a[0][2] * v[2],
        a[1][0] * v[0] + a[1][1] * v[1] + a[1][2] * v[2],
        a[2][0] * v[0] + a[2][1] * v[1] + a[2][2] * v[2],
    ]
}

/// `aᵀ·v`.
pub fn apply_transposed(a: &M3, v: [f64; 3]) -> [f64; 3] {
    [
        a[0][0] * v[0] + a[1][0] * v[1] + a[2][0] * v[2],
        a[0][1] * v[0] + a[1][1] * v[1] + a[2][1] * v[2],
        a[0][2] * v[0] + a[1][2] * v[1] + a[2][2] * v[2],
    ]
}

/// `a × b`.
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The rotation nearest `r` that is orthonormal to rounding: one step of
/// the polar iteration `(R + R⁻ᵀ)/2`, enough for the drift of a product
/// of exact rotations.
pub fn orthonormalize(r: &M3) -> M3 {
    // For R near a rotation, R⁻ᵀ ≈ R·(3I − RᵀR)/2 (one Newton–Schulz step).
    let mut rtr = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            rtr[i][j] = (0..3).map(|k| r[k][i] * r[k][j]).sum();
        }
    }
    let mut m = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = (if i == j { 3.0 } else { 0.0 } - rtr[i][j]) * 0.5;
        }
    }
    mul(r, &m)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn euler_round_trip() {
        for &(f, t, p) in &[(0.1, -0.2, 2.5), (-0.7, 0.4, -3.0), (0.0, 1.2, 0.3)] {
            let e = to_euler(&from_euler(f, t, p));
            assert!(
                (e[0] - f).abs() < 1e-14 && (e[1] - t).abs() < 1e-14 && (e[2] - p).abs() < 1e-14
            );
        }
    }

    #[test]
    fn exp_rotates_about_its_axis() {
        // A quarter turn about z takes x to y.
        let r = exp([0.0, 0.0, core::f64::consts::FRAC_PI_2]);
        let v = apply(&r, [1.0, 0.0, 0.0]);
        assert!((v[0]).abs() < 1e-15 && (v[1] - 1.0).abs() < 1e-15);
        // Small angles: exp(v×) = I + v× + O(|v|²), |v|² ≈ 1e-15.
        let r = exp([1e-8, -2e-8, 3e-8]);
        assert!((r[1][0] - 3e-8).abs() < 1e-15 && (r[0][2] + 2e-8).abs() < 1e-15);
    }

    #[test]
    fn orthonormalize_removes_drift() {
        let mut r = from_euler(0.3, -0.2, 1.0);
        r[0][0] *= 1.0 + 1e-6;
        let o = orthonormalize(&r);
        let mut worst: f64 = 0.0;
        for i in 0..3 {
            for j in 0..3 {
                let d: f64 = (0..3).map(|k| o[k][i] * o[k][j]).sum();
                worst = worst.max((d - if i == j { 1.0 } else { 0.0 }).abs());
            }
        }
        assert!(worst < 1e-11, "{worst}");
    }
}
