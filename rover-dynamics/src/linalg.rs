//! Small fixed-size vector algebra over any [`Scalar`], written out so that a
//! traced program stays straight-line.

use crate::scalar::Scalar;

/// A 3-vector.
pub type V3<S> = [S; 3];
/// A 3×3 matrix, row-major: `m[row][col]`.
pub type M3<S> = [[S; 3]; 3];

/// Constant vector.
pub fn v3<S: Scalar>(v: [f64; 3]) -> V3<S> {
    [S::cst(v[0]), S::cst(v[1]), S::cst(v[2])]
}
/// a + b.
pub fn add<S: Scalar>(a: V3<S>, b: V3<S>) -> V3<S> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
/// a − b.
pub fn sub<S: Scalar>(a: V3<S>, b: V3<S>) -> V3<S> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
/// s·a.
pub fn scale<S: Scalar>(s: S, a: V3<S>) -> V3<S> {
    [s * a[0], s * a[1], s * a[2]]
}
/// a · b.
pub fn dot<S: Scalar>(a: V3<S>, b: V3<S>) -> S {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
/// a × b (= ã·b).
pub fn cross<S: Scalar>(a: V3<S>, b: V3<S>) -> V3<S> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
/// |a|.
pub fn norm<S: Scalar>(a: V3<S>) -> S {
    dot(a, a).sqrt()
}
/// m·a.
pub fn mul<S: Scalar>(m: &M3<S>, a: V3<S>) -> V3<S> {
    [dot(m[0], a), dot(m[1], a), dot(m[2], a)]
}
/// mᵀ·a.
pub fn mul_t<S: Scalar>(m: &M3<S>, a: V3<S>) -> V3<S> {
    [
        m[0][0] * a[0] + m[1][0] * a[1] + m[2][0] * a[2],
        m[0][1] * a[0] + m[1][1] * a[1] + m[2][1] * a[2],
        m[0][2] * a[0] + m[1][2] * a[1] + m[2][2] * a[2],
    ]
}
/// a·b (matrix product).
pub fn mat_mul<S: Scalar>(a: &M3<S>, b: &M3<S>) -> M3<S> {
    let mut out = [[S::zero(); 3]; 3];
    for (r, row) in out.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c];
        }
    }
    out
}
/// aᵀ.
pub fn transpose<S: Scalar>(a: &M3<S>) -> M3<S> {
    [
        [a[0][0], a[1][0], a[2][0]],
        [a[0][1], a[1][1], a[2][1]],
        [a[0][2], a[1][2], a[2][2]],
    ]
}
/// Constant matrix.
pub fn m3<S: Scalar>(m: &[[f64; 3]; 3]) -> M3<S> {
    [v3(m[0]), v3(m[1]), v3(m[2])]
}

/// Rotation by `angle` about the unit `axis` (Rodrigues):
/// `R = I + sin α·ã + (1 − cos α)·ã²`.
pub fn axis_angle<S: Scalar>(axis: [f64; 3], angle: S) -> M3<S> {
    let (s, c) = (angle.sin(), angle.cos());
    let k = S::one() - c;
    let a: V3<S> = v3(axis);
    let mut r = [[S::zero(); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            r[i][j] = k * a[i] * a[j];
        }
        r[i][i] += c;
    }
    r[0][1] -= s * a[2];
    r[0][2] += s * a[1];
    r[1][0] += s * a[2];
    r[1][2] -= s * a[0];
    r[2][0] -= s * a[1];
    r[2][1] += s * a[0];
    r
}
