//! Weighted root-mean-square norms for error control (Hairer, Nørsett & Wanner I, §II.4, eq. 4.11).

/// `sqrt(1/n · Σ (v_i / (atol + rtol·max(|a_i|, |b_i|)))²)`: the norm of an error estimate `v`
/// for a step from `a` to `b`. Zero for an empty vector.
pub(crate) fn error_norm(v: &[f64], a: &[f64], b: &[f64], rtol: f64, atol: f64) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let sum: f64 = v
        .iter()
        .zip(a.iter().zip(b))
        .map(|(vi, (ai, bi))| {
            let scaled = vi / (atol + rtol * ai.abs().max(bi.abs()));
            scaled * scaled
        })
        .sum();
    (sum / v.len() as f64).sqrt()
}

/// `sqrt(1/n · Σ (v_i / (atol + rtol·|y_i|))²)`.
pub(crate) fn scaled_norm(v: &[f64], y: &[f64], rtol: f64, atol: f64) -> f64 {
    error_norm(v, y, y, rtol, atol)
}
